//! One animation channel's keyframes and their interpolation, as glTF 2.0 defines them
//! (§3.11 "Animations" and Appendix C "Interpolation"):
//!
//! - before the first keyframe the first value holds, after the last the last value holds;
//! - `STEP`: the value of the keyframe at or before `t`;
//! - `LINEAR`: componentwise `lerp` for translation and scale, shortest-path `slerp` for
//!   rotations;
//! - `CUBICSPLINE`: the cubic Hermite spline through the keyframe values with the stored
//!   in- and out-tangents (each scaled by the segment's duration); rotations are normalised
//!   afterwards.
use glam::{DQuat, DVec3};

/// How values between keyframes are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    Step,
    Linear,
    CubicSpline,
}

/// What a [`Track`] can hold: the three node properties a rigid animation drives.
pub trait TrackValue: Copy {
    fn lerp(a: Self, b: Self, s: f64) -> Self;
    /// `a·wa + b·wb + c·wc + d·wd` (the Hermite basis combination).
    fn combine(parts: [(Self, f64); 4]) -> Self;
    /// Brings a spline result back onto the value's domain (unit quaternions).
    fn finish(self) -> Self {
        self
    }
}

impl TrackValue for DVec3 {
    fn lerp(a: Self, b: Self, s: f64) -> Self {
        a + (b - a) * s
    }
    fn combine(parts: [(Self, f64); 4]) -> Self {
        parts.iter().fold(DVec3::ZERO, |acc, (v, w)| acc + *v * *w)
    }
}

impl TrackValue for DQuat {
    fn lerp(a: Self, b: Self, s: f64) -> Self {
        // glam's slerp takes the shorter arc (it negates `b` when the dot product is negative),
        // as the glTF appendix's reference slerp does.
        a.slerp(b, s)
    }
    fn combine(parts: [(Self, f64); 4]) -> Self {
        let v = parts.iter().fold(glam::DVec4::ZERO, |acc, (q, w)| {
            acc + glam::DVec4::from(*q) * *w
        });
        DQuat::from_vec4(v)
    }
    fn finish(self) -> Self {
        let n = self.length();
        if n > 0.0 && n.is_finite() {
            self / n
        } else {
            DQuat::IDENTITY
        }
    }
}

/// Keyframes of one property. For [`Interpolation::CubicSpline`] `values` holds three
/// entries per keyframe, `[in-tangent, value, out-tangent]`, as glTF stores them.
#[derive(Clone, Debug, PartialEq)]
pub struct Track<T> {
    /// Seconds, strictly increasing (checked by the reader).
    pub times: Vec<f64>,
    pub values: Vec<T>,
    pub interpolation: Interpolation,
}

impl<T: TrackValue> Track<T> {
    /// The keyframe value `k` (the middle element of a spline triple).
    fn value(&self, k: usize) -> T {
        match self.interpolation {
            Interpolation::CubicSpline => self.values[3 * k + 1],
            _ => self.values[k],
        }
    }

    /// First and last keyframe times.
    pub fn range(&self) -> (f64, f64) {
        (self.times[0], self.times[self.times.len() - 1])
    }

    /// The property at time `t` (seconds). A NaN `t` gives the first keyframe.
    pub fn sample(&self, t: f64) -> T {
        let n = self.times.len();
        if n == 1 || t.partial_cmp(&self.times[0]) != Some(std::cmp::Ordering::Greater) {
            return self.value(0);
        }
        if t >= self.times[n - 1] {
            return self.value(n - 1);
        }
        // Segment k with times[k] <= t < times[k + 1].
        let k = self.times.partition_point(|&x| x <= t) - 1;
        let (t0, t1) = (self.times[k], self.times[k + 1]);
        let td = t1 - t0;
        let s = (t - t0) / td;
        match self.interpolation {
            Interpolation::Step => self.value(k),
            Interpolation::Linear => T::lerp(self.value(k), self.value(k + 1), s),
            Interpolation::CubicSpline => {
                let (s2, s3) = (s * s, s * s * s);
                let v0 = self.values[3 * k + 1];
                let b0 = self.values[3 * k + 2];
                let a1 = self.values[3 * (k + 1)];
                let v1 = self.values[3 * (k + 1) + 1];
                T::combine([
                    (v0, 2.0 * s3 - 3.0 * s2 + 1.0),
                    (b0, td * (s3 - 2.0 * s2 + s)),
                    (v1, -2.0 * s3 + 3.0 * s2),
                    (a1, td * (s3 - s2)),
                ])
                .finish()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vtrack(interpolation: Interpolation, times: &[f64], values: &[[f64; 3]]) -> Track<DVec3> {
        Track {
            times: times.to_vec(),
            values: values.iter().map(|v| DVec3::from_array(*v)).collect(),
            interpolation,
        }
    }

    #[test]
    fn clamps_outside_the_keyframes() {
        let t = vtrack(
            Interpolation::Linear,
            &[1.0, 2.0],
            &[[1.0, 0.0, 0.0], [3.0, 0.0, 0.0]],
        );
        assert_eq!(t.sample(0.0).x, 1.0);
        assert_eq!(t.sample(f64::NAN).x, 1.0);
        assert_eq!(t.sample(5.0).x, 3.0);
        assert_eq!(t.sample(1.25).x, 1.5);
    }

    #[test]
    fn step_holds_the_previous_keyframe() {
        let t = vtrack(
            Interpolation::Step,
            &[0.0, 1.0, 2.0],
            &[[0.0; 3], [5.0; 3], [9.0; 3]],
        );
        assert_eq!(t.sample(0.999).x, 0.0);
        assert_eq!(t.sample(1.0).x, 5.0);
        assert_eq!(t.sample(1.5).x, 5.0);
        assert_eq!(t.sample(2.0).x, 9.0);
    }

    #[test]
    fn cubic_spline_is_the_hermite_curve() {
        // One segment of 2 s from 0 to 1 with out-tangent 3 at the start and in-tangent -1 at
        // the end (units per second). Hand-computed Hermite at s = 0.25 (t = 0.5):
        // h00 = 2s³−3s²+1 = 0.84375, h10 = s³−2s²+s = 0.140625, h01 = 0.15625,
        // h11 = s³−s² = −0.046875; p = 0·h00 + 2·3·h10 + 1·h01 + 2·(−1)·h11 = 1.09375.
        let t = vtrack(
            Interpolation::CubicSpline,
            &[0.0, 2.0],
            &[[9.0; 3], [0.0; 3], [3.0; 3], [-1.0; 3], [1.0; 3], [7.0; 3]],
        );
        assert!((t.sample(0.5).x - 1.09375).abs() < 1e-12);
        assert_eq!(t.sample(0.0).x, 0.0);
        assert_eq!(t.sample(2.0).x, 1.0);
    }

    #[test]
    fn rotations_take_the_short_way_and_stay_unit() {
        let a = DQuat::from_rotation_y(0.0);
        // −q is the same rotation as q: the slerp must not spin through 360° − 90°.
        let b = -DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
        let t = Track {
            times: vec![0.0, 1.0],
            values: vec![a, b],
            interpolation: Interpolation::Linear,
        };
        let mid = t.sample(0.5);
        let angle = mid.angle_between(DQuat::from_rotation_y(std::f64::consts::FRAC_PI_4));
        assert!(angle < 1e-9, "{angle}");
        let spline = Track {
            times: vec![0.0, 1.0],
            values: vec![
                DQuat::IDENTITY,
                a,
                DQuat::IDENTITY,
                DQuat::IDENTITY,
                b,
                DQuat::IDENTITY,
            ],
            interpolation: Interpolation::CubicSpline,
        };
        assert!((spline.sample(0.3).length() - 1.0).abs() < 1e-12);
    }
}
