//! The plane-to-plane map between the floor (in cells) and the image (in pixels), and where the
//! camera stands above the floor.
//!
//! The floor point (u, v), u along the grid's columns and v along its rows, both in cells with
//! (0, 0) the floor's top-left corner, appears at the image point H·(u, v, 1) (homogeneous).
//! Four point pairs fix H (Hartley & Zisserman, *Multiple View Geometry*, §4.1): an 8 × 8
//! linear system, solved here by Gaussian elimination with partial pivoting.

/// A homography floor → image, row-major 3 × 3 with h\[8\] = 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Homography(pub [f64; 9]);

/// A point of a plane.
pub type Point = (f64, f64);

/// The floor points of a box of pixel centres under a map straight down along the image's
/// axes ([`Homography::along_axes`]).
#[derive(Clone, Debug)]
pub struct AxisPoints {
    us: Vec<f64>,
    vs: Vec<f64>,
    x0: usize,
    y0: usize,
}

impl AxisPoints {
    /// The point of pixel `(x, y)` of the box.
    #[inline]
    pub fn at(&self, x: usize, y: usize) -> Point {
        (self.us[x - self.x0], self.vs[y - self.y0])
    }
}

impl Homography {
    /// The homography that sends `from[i]` to `to[i]`, or `None` when three of the points are
    /// (nearly) on one line.
    pub fn from_points(from: [Point; 4], to: [Point; 4]) -> Option<Homography> {
        if collinear_three(&from) || collinear_three(&to) {
            return None;
        }
        let mut a = [[0.0f64; 9]; 8];
        for i in 0..4 {
            let ((x, y), (u, v)) = (from[i], to[i]);
            a[2 * i] = [x, y, 1.0, 0.0, 0.0, 0.0, -u * x, -u * y, u];
            a[2 * i + 1] = [0.0, 0.0, 0.0, x, y, 1.0, -v * x, -v * y, v];
        }
        let h = solve8(a)?;
        let m = Homography([h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], 1.0]);
        m.0.iter().all(|x| x.is_finite()).then_some(m)
    }

    /// The floor of `w` × `h` cells seen with its corners at `corners` (top-left, top-right,
    /// bottom-right, bottom-left in the image).
    pub fn floor_to_image(w: f64, h: f64, corners: [Point; 4]) -> Option<Homography> {
        Homography::from_points([(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)], corners)
    }

    /// The pixels `(x0, y0, x1, y1)` (x0..x1 by y0..y1, one pixel of margin to the right and
    /// below) of the bounding box of floor cell `(cx, cy)`'s image, clipped to a `width` ×
    /// `height` image; `None` when a corner is on the line at infinity.
    pub fn cell_box(
        &self,
        (cx, cy): (u32, u32),
        width: usize,
        height: usize,
    ) -> Option<(usize, usize, usize, usize)> {
        let (fx, fy) = (f64::from(cx), f64::from(cy));
        self.floor_box((fx, fy), (fx + 1.0, fy + 1.0), (width, height))
    }

    /// Like [`Homography::cell_box`], for the floor's rectangle from `(u0, v0)` to `(u1, v1)`.
    pub fn floor_box(
        &self,
        (u0, v0): Point,
        (u1, v1): Point,
        (width, height): (usize, usize),
    ) -> Option<(usize, usize, usize, usize)> {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, 0.0f64, 0.0f64);
        for c in [(u0, v0), (u1, v0), (u1, v1), (u0, v1)] {
            let (x, y) = self.apply(c)?;
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n);
        Some((
            clamp(x0.floor(), width),
            clamp(y0.floor(), height),
            clamp(x1.ceil() + 1.0, width),
            clamp(y1.ceil() + 1.0, height),
        ))
    }

    /// The image of a point; `None` on the line at infinity.
    pub fn apply(&self, (x, y): Point) -> Option<Point> {
        let m = &self.0;
        let d = m[6] * x + m[7] * y + m[8];
        if d.abs() < 1e-12 {
            return None;
        }
        let (u, v) = (m[0] * x + m[1] * y + m[2], m[3] * x + m[4] * y + m[5]);
        // Dividing by 1 (an affine map, a view straight down) changes nothing: skip it.
        if d == 1.0 {
            return Some((u, v));
        }
        Some((u / d, v / d))
    }

    /// The points of the pixel centres of the image box `x0..x1` × `y0..y1` under this map
    /// (image → floor), when it is straight down along the image's axes: u then depends on
    /// the column alone and v on the row alone, each computed once. Each point equals
    /// [`Homography::apply`]'s (up to the sign of a zero). `None` for any other map.
    pub fn along_axes(
        &self,
        (x0, x1): (usize, usize),
        (y0, y1): (usize, usize),
    ) -> Option<AxisPoints> {
        let m = &self.0;
        if !(m[1] == 0.0 && m[3] == 0.0 && m[6] == 0.0 && m[7] == 0.0 && m[8] == 1.0) {
            return None;
        }
        let centre = |i: usize| i as f64 + 0.5;
        Some(AxisPoints {
            us: (x0..x1)
                .map(|x| self.apply((centre(x), 0.5)).map_or(0.0, |p| p.0))
                .collect(),
            vs: (y0..y1)
                .map(|y| self.apply((0.5, centre(y))).map_or(0.0, |p| p.1))
                .collect(),
            x0,
            y0,
        })
    }

    /// The inverse map, `None` when singular.
    pub fn inverse(&self) -> Option<Homography> {
        let m = &self.0;
        let c = [
            m[4] * m[8] - m[5] * m[7],
            m[2] * m[7] - m[1] * m[8],
            m[1] * m[5] - m[2] * m[4],
            m[5] * m[6] - m[3] * m[8],
            m[0] * m[8] - m[2] * m[6],
            m[2] * m[3] - m[0] * m[5],
            m[3] * m[7] - m[4] * m[6],
            m[1] * m[6] - m[0] * m[7],
            m[0] * m[4] - m[1] * m[3],
        ];
        let det = m[0] * c[0] + m[1] * c[3] + m[2] * c[6];
        if det.abs() < 1e-12 || c[8].abs() < 1e-300 {
            return None;
        }
        let inv = Homography(c.map(|x| x / c[8]));
        inv.0.iter().all(|x| x.is_finite()).then_some(inv)
    }

    /// Where the camera's centre stands on the floor (the nadir), for a pinhole camera with
    /// square pixels whose principal point is the image centre `centre`. `None` when the
    /// camera cannot be recovered.
    ///
    /// Straight down (the floor parallel to the image), the nadir is the point under the
    /// principal point. Otherwise the focal length follows from r1 ⟂ r2 and |r1| = |r2| for
    /// H ∝ K·\[r1 r2 t\] (Zhang 2000), and the camera centre is −Rᵀt.
    pub fn nadir(&self, centre: Point) -> Option<Point> {
        let m = &self.0;
        // Move the image origin to the principal point.
        let (cx, cy) = centre;
        let h = [
            m[0] - cx * m[6],
            m[1] - cx * m[7],
            m[2] - cx * m[8],
            m[3] - cy * m[6],
            m[4] - cy * m[7],
            m[5] - cy * m[8],
            m[6],
            m[7],
            m[8],
        ];
        let (h11, h12, h13, h21, h22, h23, h31, h32, h33) =
            (h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8]);
        let scale = (h11 * h11 + h21 * h21).sqrt().max(1e-300);
        let tilt = (h31.abs() + h32.abs()) * h33.abs().max(1e-300).recip() * scale;
        let straight = self.inverse()?.apply(centre);
        if tilt < 1e-4 {
            return straight;
        }
        let ortho = (-(h11 * h12 + h21 * h22), h31 * h32);
        let equal = (
            -(h11 * h11 + h21 * h21 - h12 * h12 - h22 * h22),
            h31 * h31 - h32 * h32,
        );
        let (num, den) = if ortho.1.abs() > equal.1.abs() {
            ortho
        } else {
            equal
        };
        let f2 = num / den;
        if !(f2.is_finite() && f2 > 0.0) {
            return straight;
        }
        let f = f2.sqrt();
        let k = |c: [f64; 3]| [c[0] / f, c[1] / f, c[2]];
        let (a1, a2, a3) = (k([h11, h21, h31]), k([h12, h22, h32]), k([h13, h23, h33]));
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let lambda = 1.0 / norm(a1);
        let r1 = a1.map(|x| x * lambda);
        let r2 = a2.map(|x| x * lambda);
        let t = a3.map(|x| x * lambda);
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let c = (-dot(r1, t), -dot(r2, t));
        (c.0.is_finite() && c.1.is_finite()).then_some(c)
    }
}

/// Whether three of the four points are (nearly) on one line.
fn collinear_three(p: &[Point; 4]) -> bool {
    let size = p
        .iter()
        .flat_map(|a| {
            p.iter()
                .map(move |b| (a.0 - b.0).abs().max((a.1 - b.1).abs()))
        })
        .fold(0.0, f64::max);
    (0..4).any(|skip| {
        let q: Vec<Point> = (0..4).filter(|&i| i != skip).map(|i| p[i]).collect();
        let area = (q[1].0 - q[0].0) * (q[2].1 - q[0].1) - (q[1].1 - q[0].1) * (q[2].0 - q[0].0);
        // NaN corners count as collinear.
        area.abs().partial_cmp(&(1e-9 * size * size)) != Some(std::cmp::Ordering::Greater)
    })
}

/// Solves the 8 × 8 system \[A | b\] (b in the last column).
fn solve8(mut a: [[f64; 9]; 8]) -> Option<[f64; 8]> {
    for col in 0..8 {
        let pivot = (col..8).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-10 {
            return None;
        }
        a.swap(col, pivot);
        let pivot_row = a[col];
        for (row, r) in a.iter_mut().enumerate() {
            if row != col {
                let f = r[col] / pivot_row[col];
                for (x, p) in r.iter_mut().zip(pivot_row).skip(col) {
                    *x -= f * p;
                }
            }
        }
    }
    let mut x = [0.0; 8];
    for (i, (xi, row)) in x.iter_mut().zip(&a).enumerate() {
        *xi = row[8] / row[i];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Point, b: Point, tol: f64) -> bool {
        (a.0 - b.0).abs() < tol && (a.1 - b.1).abs() < tol
    }

    #[test]
    fn maps_the_corners_and_back() {
        let corners = [(12.0, 30.0), (410.0, 8.0), (450.0, 300.0), (-5.0, 280.0)];
        let h = Homography::floor_to_image(20.0, 14.0, corners).unwrap();
        let inv = h.inverse().unwrap();
        for (f, c) in [(0.0, 0.0), (20.0, 0.0), (20.0, 14.0), (0.0, 14.0)]
            .into_iter()
            .zip(corners)
        {
            assert!(close(h.apply(f).unwrap(), c, 1e-6));
            assert!(close(inv.apply(c).unwrap(), f, 1e-6));
        }
        let p = (7.3, 2.9);
        assert!(close(inv.apply(h.apply(p).unwrap()).unwrap(), p, 1e-9));
    }

    #[test]
    fn three_points_on_a_line_have_no_homography() {
        let corners = [(0.0, 0.0), (10.0, 0.0), (20.0, 0.0), (0.0, 10.0)];
        assert!(Homography::floor_to_image(4.0, 4.0, corners).is_none());
    }

    /// A view straight down along the image's axes: the points of `along_axes` are the
    /// points `apply` gives, pixel for pixel; a tilted view has none.
    #[test]
    fn points_along_the_axes_are_the_applied_points() {
        let straight = Homography::floor_to_image(
            7.0,
            5.0,
            [(3.0, 2.0), (143.0, 2.0), (143.0, 102.0), (3.0, 102.0)],
        )
        .unwrap()
        .inverse()
        .unwrap();
        let points = straight.along_axes((0, 150), (0, 110)).unwrap();
        for y in 0..110 {
            for x in 0..150 {
                let want = straight.apply((x as f64 + 0.5, y as f64 + 0.5)).unwrap();
                assert_eq!(points.at(x, y), want, "({x}, {y})");
            }
        }
        let tilted = Homography::floor_to_image(
            7.0,
            5.0,
            [(3.0, 2.0), (143.0, 9.0), (150.0, 102.0), (0.0, 95.0)],
        )
        .unwrap()
        .inverse()
        .unwrap();
        assert!(tilted.along_axes((0, 150), (0, 110)).is_none());
    }

    /// A pinhole camera at a known place: the nadir found from the four corners is where it
    /// stands.
    #[test]
    fn finds_the_nadir_of_a_tilted_camera() {
        let (w, h) = (24.0, 16.0);
        let cam = [30.0, -20.0, 60.0];
        let target = [12.0, 8.0, 0.0];
        let f = 900.0;
        let (cx, cy) = (400.0, 300.0);
        let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let unit = |a: [f64; 3]| {
            let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            a.map(|x| x / n)
        };
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let d = unit(sub(target, cam));
        let right = unit(cross(d, [0.0, -1.0, 0.0]));
        let down = cross(d, right);
        let project = |p: [f64; 3]| {
            let q = sub(p, cam);
            let z = dot(q, d);
            (cx + f * dot(q, right) / z, cy + f * dot(q, down) / z)
        };
        let corners = [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)].map(|(x, y)| project([x, y, 0.0]));
        let hm = Homography::floor_to_image(w, h, corners).unwrap();
        let n = hm.nadir((cx, cy)).unwrap();
        assert!(close(n, (30.0, -20.0), 1e-6), "{n:?}");
        // Straight down: the point under the image centre.
        let flat = [(0.0, 0.0), (480.0, 0.0), (480.0, 320.0), (0.0, 320.0)];
        let hm = Homography::floor_to_image(w, h, flat).unwrap();
        assert!(close(hm.nadir((240.0, 160.0)).unwrap(), (12.0, 8.0), 1e-9));
    }
}
