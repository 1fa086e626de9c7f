//! What a pixel shows: floor, robot, goal, obstacle, or a colour that cannot be told.
//!
//! Colours are judged after white balance on the floor (the floor's median colour becomes
//! grey), by hue, saturation s = (max − min) / max and chroma c = (max − min) relative to the
//! floor's brightness. Robots and goals need less colour than obstacles (see the constants). A shadow darkens the floor but keeps its hue-less grey (s stays low),
//! so a shadow stays floor; a pale obstacle as bright as the lit floor (no shadow) needs
//! less saturation; a robot in a shadow keeps its hue. The floor's lit brightness is
//! its median, so chroma does not depend on exposure.

/// A colour as a hue in degrees (0 red, 120 green, 240 blue).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hue(pub f64);

impl Hue {
    /// Red, the default colour of robots.
    pub const RED: Hue = Hue(0.0);
    /// Green, the default colour of goals.
    pub const GREEN: Hue = Hue(120.0);

    /// Parses `red`, `green`, `blue`, `yellow`, `cyan`, `magenta`, `orange`, `#rrggbb` or a hue
    /// in degrees (`hue:200`).
    pub fn parse(text: &str) -> Result<Hue, String> {
        let t = text.trim().to_ascii_lowercase();
        let named = match t.as_str() {
            "red" => Some(0.0),
            "orange" => Some(30.0),
            "yellow" => Some(60.0),
            "green" => Some(120.0),
            "cyan" => Some(180.0),
            "blue" => Some(240.0),
            "magenta" | "purple" => Some(300.0),
            _ => None,
        };
        if let Some(h) = named {
            return Ok(Hue(h));
        }
        if let Some(deg) = t.strip_prefix("hue:") {
            return match deg.parse::<f64>() {
                Ok(d) if (0.0..360.0).contains(&d) => Ok(Hue(d)),
                _ => Err(format!("`{text}`: a hue is 0 to 359.9 degrees")),
            };
        }
        if let Some(hex) = t.strip_prefix('#') {
            if hex.len() == 6 && hex.chars().all(|c| c.is_ascii_hexdigit()) {
                let v = u32::from_str_radix(hex, 16).unwrap_or(0);
                let rgb = [(v >> 16) as f64, ((v >> 8) & 255) as f64, (v & 255) as f64];
                let (hue, s) = hue_saturation(rgb);
                if s < 0.4 {
                    return Err(format!(
                        "`{text}` is too grey to mark robots or goals (saturation {s:.2}, at least 0.40)"
                    ));
                }
                return Ok(Hue(hue));
            }
        }
        Err(format!(
            "`{text}`: give red, orange, yellow, green, cyan, blue, magenta, #rrggbb or hue:DEGREES"
        ))
    }

    /// The angle between two hues, 0 to 180 degrees.
    pub fn distance(self, other: f64) -> f64 {
        let d = rem_euclid(self.0 - other, 360.0);
        d.min(360.0 - d)
    }
}

/// `x.rem_euclid(m)` for `m` > 0, without the remainder's division when |x| < m (then
/// `x % m` is `x`, and the result is `x`, or `x + m` when negative, as `rem_euclid` gives).
#[inline]
fn rem_euclid(x: f64, m: f64) -> f64 {
    if x.abs() < m {
        if x < 0.0 {
            x + m
        } else {
            x
        }
    } else {
        x.rem_euclid(m)
    }
}

/// The larger of two colour values, neither NaN nor −0 (products of bytes and positive
/// gains): as `f64::max`, in one comparison.
#[inline]
fn larger(a: f64, b: f64) -> f64 {
    if a >= b {
        a
    } else {
        b
    }
}

/// The smaller of two colour values, neither NaN nor −0: as `f64::min`.
#[inline]
fn smaller(a: f64, b: f64) -> f64 {
    if a <= b {
        a
    } else {
        b
    }
}

/// Hue in degrees and saturation of an RGB colour.
pub fn hue_saturation([r, g, b]: [f64; 3]) -> (f64, f64) {
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    let c = max - min;
    if max <= 0.0 || c <= 0.0 {
        return (0.0, 0.0);
    }
    let h = if max == r {
        60.0 * rem_euclid((g - b) / c, 6.0)
    } else if max == g {
        60.0 * ((b - r) / c + 2.0)
    } else {
        60.0 * ((r - g) / c + 4.0)
    };
    (h, c / max)
}

/// What one pixel shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Class {
    /// Floor, lit or in shadow, with its lines and texture.
    Floor = 0,
    /// The robots' colour.
    Robot = 1,
    /// The goals' colour.
    Goal = 2,
    /// A coloured obstacle (any clear colour far from the robots' and the goals').
    Obstacle = 3,
    /// A clear colour near but not at the robots' or goals' (a colour that cannot be told), or
    /// too dark to judge.
    Unsure = 4,
}

/// Pixels classified by colour after white balance on the floor.
#[derive(Clone, Copy, Debug)]
pub struct Classifier {
    gain: [f64; 3],
    robot: Hue,
    goal: Hue,
    /// The floor's brightness (its brightest channel) and chromaticity (channels over their
    /// sum), before white balance.
    floor_bright: f64,
    floor_chromaticity: [f64; 3],
    /// The saturation after white balance from which a lit floor-coloured pixel leans pale
    /// (see [`Classifier::leaning`]).
    lean_tint: f64,
    /// The floor's colour after white balance in the view's shadows, if known
    /// ([`super::pale::shade`]).
    shade: Option<[f64; 3]>,
}

/// Saturation and chroma (max − min, relative to the lit floor) of a robot's or goal's pixel:
/// small marks are blurred and their colour washed out by JPEG.
const MARK_COLOUR: (f64, f64) = (0.25, 0.05);
/// Saturation and chroma of a faint mark's pixel, its colour averaged over a few pixels around
/// it ([`Classifier::faint_mark`]): half a mark's; and its least brightness (its brightest
/// channel, relative to the lit floor): lit, since a shadow's tint is the light's.
pub const FAINT_MARK: (f64, f64, f64) = (0.12, 0.025, 0.85);
/// Saturation and chroma of an obstacle's pixel: higher, since shadows under a blue sky are
/// bluish after white balance on the sunlit floor.
const OBSTACLE_COLOUR: (f64, f64) = (0.3, 0.1);
/// Brightness (relative to the lit floor) at which a pixel is no shadow, and the saturation
/// that then suffices for an obstacle (pale shelves), with the chroma above: a mark's.
const LIT_OBSTACLE: (f64, f64) = (0.85, MARK_COLOUR.0);
/// A shadow lit by the sky alone: at most this bright (relative to the lit floor) and this
/// saturated, of a hue in [`SKY_HUES`] (a clear blue or cyan obstacle is more saturated, and
/// its lit top brighter).
const SKY_SHADOW: (f64, f64) = (0.7, 0.45);
/// The hues of the sky's light, in degrees (cyan to blue).
const SKY_HUES: (f64, f64) = (180.0, 260.0);
/// Half-width of the robots' and the goals' hue bands, in degrees (robots are a clear colour;
/// goals are paint or tape on the floor, whose green varies more).
const HUE_BAND: (f64, f64) = (25.0, 35.0);
/// Hues this much beyond a band cannot be told apart from it.
const HUE_DOUBT: f64 = 10.0;
/// A mark by its colour before white balance differs from the floor's chromaticity by at
/// least this much in one channel.
const RAW_APART: f64 = 0.06;

impl Classifier {
    /// A classifier for a floor whose median colour (0–255 per channel) is `floor`.
    pub fn new(floor: [f64; 3], robot: Hue, goal: Hue) -> Classifier {
        let bright = floor.iter().copied().fold(0.0, f64::max).max(1.0);
        let gain = floor.map(|c| 1.0 / c.max(bright * 0.05));
        let sum = floor.iter().sum::<f64>().max(1.0);
        Classifier {
            gain,
            robot,
            goal,
            floor_bright: bright,
            floor_chromaticity: floor.map(|c| c / sum),
            lean_tint: super::pale::LEANING.2,
            shade: None,
        }
    }

    /// The classifier with the saturation from which a lit pixel leans pale raised to
    /// `tint`, if that is more than the loose limit of [`super::pale::LEANING`]: on a dark,
    /// noisy or finely tinted floor the lit floor's own pixels reach that limit (see
    /// [`super::pale::lean_tint`]).
    pub fn with_lean_tint(self, tint: f64) -> Classifier {
        Classifier {
            lean_tint: tint.max(super::pale::LEANING.2),
            ..self
        }
    }

    /// The classifier with the floor's colour in the view's shadows (see
    /// [`super::pale::shade`]).
    pub fn with_shade(self, shade: Option<[f64; 3]>) -> Classifier {
        Classifier { shade, ..self }
    }

    /// Whether a colour after white balance leans pale: at least [`super::pale::LEANING`]'s
    /// brightness, or lit and at least this classifier's leaning saturation.
    pub fn leaning(&self, balanced: [f64; 3]) -> bool {
        super::pale::is_leaning_with(balanced, self.lean_tint)
    }

    /// Whether a colour after white balance that leans pale by its tint, not its brightness,
    /// is the floor under a mix of the sun's and the sky's light
    /// ([`super::pale::shade_explains`]; never when the view's shadows' colour is unknown).
    pub fn shaded(&self, balanced: [f64; 3]) -> bool {
        self.shaded_with(balanced, self.lean_tint)
    }

    /// The tint a colour after white balance keeps however the shadows' light mixes with the
    /// sun's ([`super::pale::least_relit_saturation`]); its own saturation when the view's
    /// shadows' colour is unknown.
    pub fn unexplained_tint(&self, balanced: [f64; 3]) -> f64 {
        self.shade.map_or_else(
            || super::pale::saturation(balanced),
            |shade| super::pale::least_relit_saturation(balanced, shade),
        )
    }

    /// Like [`Classifier::shaded`], relit less saturated than `tint`.
    pub fn shaded_with(&self, balanced: [f64; 3], tint: f64) -> bool {
        self.shade.is_some_and(|shade| {
            balanced.iter().all(|&c| c < super::pale::LEANING.0)
                && super::pale::shade_explains(balanced, shade, tint)
        })
    }
    /// The mark (robot or goal) a pixel shows by its colour before white balance, if any:
    /// a clear colour (as a mark's, relative to the lit floor) within a mark's hue band and
    /// at least `RAW_APART` (0.06) in chromaticity from the floor's. A floor of a clear colour,
    /// beige say, turns a pale mark's balanced hue (a pale green goal on it becomes cyan);
    /// see [`super::tinted`].
    pub fn raw_mark(&self, p: [u8; 3]) -> Option<Class> {
        let rgb = p.map(f64::from);
        let (max, min) = (
            rgb[0].max(rgb[1]).max(rgb[2]),
            rgb[0].min(rgb[1]).min(rgb[2]),
        );
        let chroma = max - min;
        let sum = rgb.iter().sum::<f64>();
        if max <= 0.0 || chroma < MARK_COLOUR.1 * self.floor_bright || chroma < MARK_COLOUR.0 * max
        {
            return None;
        }
        let apart = (0..3)
            .map(|c| (rgb[c] / sum - self.floor_chromaticity[c]).abs())
            .fold(0.0, f64::max);
        if apart < RAW_APART {
            return None;
        }
        self.mark_of_hue(hue_saturation(rgb).0)
    }

    /// The mark (robot or goal) whose hue band `hue` falls in, the robots' first where the
    /// bands meet nearer to their hue.
    fn mark_of_hue(&self, hue: f64) -> Option<Class> {
        let (dr, dg) = (self.robot.distance(hue), self.goal.distance(hue));
        if dr <= HUE_BAND.0 && dr < dg {
            Some(Class::Robot)
        } else if dg <= HUE_BAND.1 {
            Some(Class::Goal)
        } else {
            None
        }
    }

    /// The mark whose hue band a colour (before white balance) falls in, with half the colour
    /// a mark's pixel needs, lit ([`FAINT_MARK`]): the washed-out rim and arms of a small mark
    /// in a noisy view, around its clear pixels, or a small goal's paint washed out whole.
    pub fn faint_mark(&self, p: [u8; 3]) -> Option<Class> {
        let (rgb, max, min) = self.balanced_extremes(p);
        let chroma = max - min;
        if max < FAINT_MARK.2 || chroma < FAINT_MARK.1 || chroma < FAINT_MARK.0 * max {
            return None;
        }
        self.mark_of_hue(hue_saturation(rgb).0)
    }

    /// Whether a colour (before white balance) has a hue within `degrees` of the mark
    /// `class`'s (robot or goal) after white balance.
    pub fn near_hue_of(&self, p: [u8; 3], class: Class, degrees: f64) -> bool {
        let (hue, s) = hue_saturation(self.balanced(p));
        let mark = if class == Class::Robot {
            self.robot
        } else {
            self.goal
        };
        s > 0.0 && mark.distance(hue) <= degrees
    }

    /// The signed angle (−180 to 180 degrees) from the robots' hue to the hue of a colour
    /// (before white balance) after white balance, and its saturation then.
    pub fn hue_from_robots(&self, p: [u8; 3]) -> (f64, f64) {
        self.hue_from(p, Class::Robot)
    }

    /// Like [`Classifier::hue_from_robots`], from the hue of the mark `class` (robot or
    /// goal).
    pub fn hue_from(&self, p: [u8; 3], class: Class) -> (f64, f64) {
        let (hue, s) = hue_saturation(self.balanced(p));
        let mark = if class == Class::Robot {
            self.robot
        } else {
            self.goal
        };
        (rem_euclid(hue - mark.0 + 180.0, 360.0) - 180.0, s)
    }

    /// Whether a colour after white balance has a mark's hue (within a robot's or a goal's hue
    /// band, or the doubt beyond it): the glow a robot or goal spreads into the floor around it.
    pub fn of_a_marks_hue(&self, balanced: [f64; 3]) -> bool {
        let (hue, s) = hue_saturation(balanced);
        s > 0.0
            && (self.robot.distance(hue) <= HUE_BAND.0 + HUE_DOUBT
                || self.goal.distance(hue) <= HUE_BAND.1 + HUE_DOUBT)
    }

    /// A pixel's colour after white balance on the floor: the lit floor's median is 1 in
    /// every channel.
    pub fn balanced(&self, p: [u8; 3]) -> [f64; 3] {
        [0, 1, 2].map(|c| f64::from(p[c]) * self.gain[c])
    }

    /// A pixel's colour after white balance, with its largest and smallest channel.
    #[inline]
    fn balanced_extremes(&self, p: [u8; 3]) -> ([f64; 3], f64, f64) {
        let rgb = [
            f64::from(p[0]) * self.gain[0],
            f64::from(p[1]) * self.gain[1],
            f64::from(p[2]) * self.gain[2],
        ];
        let max = larger(larger(rgb[0], rgb[1]), rgb[2]);
        let min = smaller(smaller(rgb[0], rgb[1]), rgb[2]);
        (rgb, max, min)
    }

    /// Whether [`Classifier::classify`] says floor at its first test: too little colour for
    /// a mark (or black).
    #[inline]
    fn greyish(max: f64, min: f64) -> bool {
        let chroma = max - min;
        (max <= 0.0) | !((chroma >= MARK_COLOUR.1) & (chroma >= MARK_COLOUR.0 * max))
    }

    /// [`Classifier::classify`]'s first test for every pixel of `row` (3 bytes a pixel) into
    /// `grey`: `true` where it says floor by that test alone. One loop without branches, for
    /// a row of pixels that are mostly floor.
    pub fn greyish_row(&self, row: &[u8], grey: &mut [bool]) {
        for (g, p) in grey.iter_mut().zip(row.chunks_exact(3)) {
            let (_, max, min) = self.balanced_extremes([p[0], p[1], p[2]]);
            *g = Classifier::greyish(max, min);
        }
    }

    /// The class of one pixel by its colour after white balance.
    pub fn classify(&self, p: [u8; 3]) -> Class {
        let (rgb, max, min) = self.balanced_extremes(p);
        if Classifier::greyish(max, min) {
            return Class::Floor;
        }
        let chroma = max - min;
        let clear = |(s, c): (f64, f64)| chroma >= c && chroma >= s * max;
        let (hue, _) = hue_saturation(rgb);
        let (dr, dg) = (self.robot.distance(hue), self.goal.distance(hue));
        if dr <= HUE_BAND.0 && dr < dg {
            Class::Robot
        } else if dg <= HUE_BAND.1 {
            Class::Goal
        } else if !(clear(OBSTACLE_COLOUR)
            || (max >= LIT_OBSTACLE.0 && clear((LIT_OBSTACLE.1, OBSTACLE_COLOUR.1))))
        {
            Class::Floor
        } else if max < SKY_SHADOW.0
            && chroma < SKY_SHADOW.1 * max
            && (SKY_HUES.0..=SKY_HUES.1).contains(&hue)
        {
            // Floor in a shadow, lit by the sky alone: darker and bluish after white
            // balance on the sunlit floor.
            Class::Floor
        } else if dr <= HUE_BAND.0 + HUE_DOUBT || dg <= HUE_BAND.1 + HUE_DOUBT {
            Class::Unsure
        } else {
            Class::Obstacle
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn classifier() -> Classifier {
        Classifier::new([160.0, 150.0, 130.0], Hue::RED, Hue::GREEN)
    }

    #[test]
    fn shadows_stay_floor_and_shaded_robots_stay_robots() {
        let c = classifier();
        assert_eq!(c.classify([160, 150, 130]), Class::Floor);
        assert_eq!(c.classify([40, 37, 33]), Class::Floor);
        assert_eq!(c.classify([5, 4, 3]), Class::Floor);
        assert_eq!(c.classify([170, 25, 20]), Class::Robot);
        assert_eq!(c.classify([45, 8, 6]), Class::Robot);
        assert_eq!(c.classify([20, 120, 30]), Class::Goal);
        assert_eq!(c.classify([30, 60, 150]), Class::Obstacle);
        // Amber, between red and yellow: neither a robot's colour nor clearly another.
        assert_eq!(c.classify([220, 120, 20]), Class::Unsure);
    }

    #[test]
    fn a_marks_glow_has_its_hue() {
        let c = classifier();
        // After white balance: faintly pink, faintly green, faintly blue, grey.
        assert!(c.of_a_marks_hue([1.2, 1.05, 1.06]));
        assert!(c.of_a_marks_hue([1.0, 1.15, 1.02]));
        assert!(!c.of_a_marks_hue([1.0, 1.05, 1.2]));
        assert!(!c.of_a_marks_hue([1.1, 1.1, 1.1]));
    }

    #[test]
    fn a_pale_obstacle_is_told_from_a_bluish_shadow() {
        let c = Classifier::new([150.0, 150.0, 150.0], Hue::RED, Hue::GREEN);
        // Pale blue, brighter than the floor: saturation 0.27.
        assert_eq!(c.classify([150, 175, 205]), Class::Obstacle);
        // The same tint in a shadow (two thirds as bright): floor.
        assert_eq!(c.classify([75, 88, 103]), Class::Floor);
    }

    #[test]
    fn a_shadow_lit_by_the_sky_is_floor_and_a_blue_shelf_an_obstacle() {
        let c = Classifier::new([150.0, 150.0, 150.0], Hue::RED, Hue::GREEN);
        // Half as bright as the lit floor and bluish (saturation 0.33): the sky's light.
        assert_eq!(c.classify([54, 60, 80]), Class::Floor);
        // A blue shelf's shaded side: as dark, far more saturated.
        assert_eq!(c.classify([20, 30, 80]), Class::Obstacle);
        // A dark magenta, of no sky hue: an obstacle.
        assert_eq!(c.classify([70, 30, 70]), Class::Obstacle);
    }

    #[test]
    fn a_tinted_light_is_balanced_away() {
        // Warm light: the floor reads orange-ish, and a grey shadow of it too.
        let c = Classifier::new([200.0, 150.0, 100.0], Hue::RED, Hue::GREEN);
        assert_eq!(c.classify([100, 75, 50]), Class::Floor);
        assert_eq!(c.classify([200, 40, 20]), Class::Robot);
    }

    #[test]
    fn colours_parse() {
        assert_eq!(Hue::parse("red").unwrap(), Hue(0.0));
        assert_eq!(Hue::parse("hue:200").unwrap(), Hue(200.0));
        assert!((Hue::parse("#0000ff").unwrap().0 - 240.0).abs() < 1e-9);
        assert!(Hue::parse("#808080").unwrap_err().contains("too grey"));
        assert!(Hue::parse("hue:400").is_err());
        assert!(Hue::parse("mauve").is_err());
        assert!((Hue(350.0).distance(10.0) - 20.0).abs() < 1e-9);
    }
}
