//! Where each brick goes in a front view: the wall's segments stacked one above the other
//! (segments never support each other), each from its own left edge, so that a wall of several
//! segments, such as the 17.7 m MBZIRC wall, is drawn at the scale of a one-segment wall.
//! Shared by the wall SVG and the mission replay's wall panel.

use mason_wall::{Wall, BRICK_HEIGHT};

/// Height, in metres, of the caption above each segment of a wall with more than one.
pub const CAPTION_M: f64 = 0.25;

/// One segment's band in the drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    /// The segment number.
    pub segment: u32,
    /// Top of the band (its caption, if any) in metres from the top of the drawing.
    pub top: f64,
    /// Levels in the segment.
    pub levels: u32,
}

/// A brick's place in the drawing, in metres.
#[derive(Clone, Debug, PartialEq)]
pub struct Spot {
    /// Left and right edges, from the drawing's left.
    pub x0: f64,
    /// Right edge.
    pub x1: f64,
    /// Top edge, from the top of the drawing.
    pub y: f64,
}

/// The front view of a wall: its bands, every brick's spot (by brick index) and the size.
#[derive(Clone, Debug, PartialEq)]
pub struct FrontLayout {
    /// One band per segment, top to bottom in segment order.
    pub bands: Vec<Band>,
    /// Every brick's spot, in brick index order.
    pub spots: Vec<Spot>,
    /// Width in metres (the widest segment).
    pub width: f64,
    /// Height in metres.
    pub height: f64,
    /// Whether bands carry captions (more than one segment).
    pub captions: bool,
}

/// Stacks the wall's segments, segment 1 on top, each band as tall as its own levels.
pub fn front_layout(wall: &Wall) -> FrontLayout {
    let mut segments: Vec<u32> = wall.bricks().iter().map(|b| b.segment).collect();
    segments.sort_unstable();
    segments.dedup();
    let captions = segments.len() > 1;
    let caption = if captions { CAPTION_M } else { 0.0 };
    let mut bands = Vec::with_capacity(segments.len());
    let mut left = Vec::with_capacity(segments.len());
    let (mut top, mut width) = (0.0, 0.0f64);
    for &segment in &segments {
        let mine = || wall.bricks().iter().filter(move |b| b.segment == segment);
        let x_min = mine().map(|b| b.footprint.x0).fold(f64::INFINITY, f64::min);
        let x_max = mine()
            .map(|b| b.footprint.x1)
            .fold(f64::NEG_INFINITY, f64::max);
        let levels = mine().map(|b| b.level).max().unwrap_or(1);
        width = width.max(x_max - x_min);
        bands.push(Band {
            segment,
            top,
            levels,
        });
        left.push(x_min);
        top += caption + f64::from(levels) * BRICK_HEIGHT;
    }
    let spots = wall
        .bricks()
        .iter()
        .map(|b| {
            let i = segments.binary_search(&b.segment).unwrap_or(0);
            let band = &bands[i];
            Spot {
                x0: b.footprint.x0 - left[i],
                x1: b.footprint.x1 - left[i],
                y: band.top
                    + caption
                    + f64::from(band.levels - b.level.min(band.levels)) * BRICK_HEIGHT,
            }
        })
        .collect();
    FrontLayout {
        bands,
        spots,
        width,
        height: top,
        captions,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_are_stacked_each_from_its_own_left_edge() {
        let wall = mason_wall::parse_layer_text("R R | G\nB R | R R", "w").unwrap();
        let layout = front_layout(&wall);
        assert_eq!(layout.bands.len(), 2);
        assert!(layout.captions);
        // The widest segment is the first: blue + red, 1.5 m.
        assert!((layout.width - 1.5).abs() < 1e-9, "{}", layout.width);
        assert!((layout.height - 2.0 * (CAPTION_M + 0.4)).abs() < 1e-9);
        for (b, spot) in wall.bricks().iter().zip(&layout.spots) {
            let band = &layout.bands[(b.segment - layout.bands[0].segment) as usize];
            assert!(spot.x0 >= -1e-9 && spot.x1 <= layout.width + 1e-9);
            assert!(spot.y >= band.top + CAPTION_M - 1e-9);
            assert!(spot.y + BRICK_HEIGHT <= band.top + CAPTION_M + 0.4 + 1e-9);
        }
        // A one-segment wall has no captions and keeps its width.
        let one = front_layout(&mason_wall::parse_layer_text("R G B", "one").unwrap());
        assert!(!one.captions);
        assert!((one.width - 2.1).abs() < 1e-9 && (one.height - 0.2).abs() < 1e-9);
    }
}
