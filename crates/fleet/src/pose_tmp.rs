//! TEMPORARY: stands in for `mason_report::PoseSampler` until report's version is merged.
#![allow(missing_docs)]

pub struct PoseSampler {
    uav: u32,
    last: Option<(f64, (f64, f64, f64))>,
    yaw: f64,
    due: bool,
}

impl PoseSampler {
    pub fn new(uav: u32) -> Self {
        PoseSampler { uav, last: None, yaw: 0.0, due: true }
    }
    pub fn uav(&self) -> u32 {
        self.uav
    }
    pub fn mark_due(&mut self) {
        self.due = true;
    }
    pub fn sample(&mut self, t: f64, (x, y, z): (f64, f64, f64)) -> Option<mason_report::UavPose> {
        let period = 1.0 / mason_report::POSE_RATE_HZ;
        let due = self.due || self.last.is_none_or(|(t0, _)| t - t0 >= period);
        if !due {
            return None;
        }
        if let Some((_, (x0, y0, _))) = self.last {
            if (x - x0).hypot(y - y0) > 1e-6 {
                self.yaw = (y - y0).atan2(x - x0);
            }
        }
        self.last = Some((t, (x, y, z)));
        self.due = false;
        Some(mason_report::UavPose { x, y, z, yaw: self.yaw })
    }
}
