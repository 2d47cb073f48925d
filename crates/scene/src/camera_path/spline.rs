//! Position along the path: the centripetal Catmull-Rom curve and its monotone time map.
use super::CameraPath;
use glam::DVec3;

impl CameraPath {
    /// Keyframe position j, with the reflected phantoms at j = −1 and j = n.
    pub(super) fn point(&self, j: isize) -> DVec3 {
        let keys = &self.keyframes;
        let n = keys.len() as isize;
        let p = |j: isize| keys[j as usize].position;
        match j {
            -1 if n >= 2 => 2.0 * p(0) - p(1),
            -1 => p(0),
            j if j == n && n >= 2 => 2.0 * p(n - 1) - p(n - 2),
            j if j == n => p(n - 1),
            j => p(j),
        }
    }

    /// Centripetal knot interval between points j and j+1 (phantoms included).
    pub(super) fn knot_interval(&self, j: isize) -> f64 {
        self.point(j).distance(self.point(j + 1)).sqrt()
    }

    /// Slope of τ(t) at keyframe j: monotone-cubic (PCHIP) slopes of the points (T_j, τ_j).
    pub(super) fn knot_rate(&self, j: usize) -> f64 {
        let keys = &self.keyframes;
        let n = keys.len();
        let dt = |j: usize| keys[j + 1].time - keys[j].time;
        let secant = |j: usize| self.knot_interval(j as isize) / dt(j);
        if n == 2 {
            return secant(0);
        }
        // Three-point end formula, clipped at zero to stay monotone (SciPy's `_edge_case`; its
        // second clip, to 3× the secant, cannot trigger when all secants are non-negative).
        let end = |h0: f64, h1: f64, m0: f64, m1: f64| {
            (((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)).max(0.0)
        };
        if j == 0 {
            return end(dt(0), dt(1), secant(0), secant(1));
        }
        if j == n - 1 {
            return end(dt(n - 2), dt(n - 3), secant(n - 2), secant(n - 3));
        }
        let (m0, m1) = (secant(j - 1), secant(j));
        if m0 == 0.0 || m1 == 0.0 {
            // A pause on either side: stop there, so velocity is continuous (zero) across it.
            return 0.0;
        }
        let (h0, h1) = (dt(j - 1), dt(j));
        let (w1, w2) = (2.0 * h1 + h0, h1 + 2.0 * h0);
        (w1 + w2) / (w1 / m0 + w2 / m1)
    }

    /// τ(t) − τ_i inside segment i, in [0, h_i]: the cubic Hermite of the monotone map.
    pub(super) fn knot_progress(&self, i: usize, t: f64) -> f64 {
        let keys = &self.keyframes;
        let h = self.knot_interval(i as isize);
        let dt = keys[i + 1].time - keys[i].time;
        let s = (t - keys[i].time) / dt;
        let (s2, s3) = (s * s, s * s * s);
        let u = (s3 - 2.0 * s2 + s) * dt * self.knot_rate(i)
            + (3.0 * s2 - 2.0 * s3) * h
            + (s3 - s2) * dt * self.knot_rate(i + 1);
        // Monotone in exact arithmetic; the clamp only absorbs rounding at the ends.
        u.clamp(0.0, h)
    }

    /// Position at time t inside segment i (T_i ≤ t < T_{i+1}).
    pub(super) fn position(&self, i: usize, t: f64) -> DVec3 {
        if self.knot_interval(i as isize) == 0.0 {
            return self.keyframes[i].position;
        }
        self.curve(i, self.knot_progress(i, t))
    }

    /// The centripetal spline on segment i at local knot parameter u ∈ [0, h_i], h_i > 0.
    pub(super) fn curve(&self, i: usize, u: f64) -> DVec3 {
        let j = i as isize;
        let points = [-1, 0, 1, 2].map(|k| self.point(j + k));
        let intervals = [-1, 0, 1].map(|k| self.knot_interval(j + k));
        catmull_rom_segment(points, intervals, u)
    }
}

/// The Barry–Goldman pyramid for the segment P1→P2 with knots (−h0, 0, h1, h1 + h2), at local
/// knot parameter `u` ∈ [0, h1], h1 > 0. A zero h0 or h2 (a point repeated at the segment's end)
/// is the limit of its linear term: (P1 − P0)/h0 has length h0 and vanishes, so A1 = P1.
fn catmull_rom_segment(p: [DVec3; 4], h: [f64; 3], u: f64) -> DVec3 {
    let [p0, p1, p2, p3] = p;
    let [h0, h1, h2] = h;
    if u <= 0.0 {
        return p1;
    }
    if u >= h1 {
        return p2;
    }
    let a1 = if h0 == 0.0 {
        p1
    } else {
        p1 + (p1 - p0) * (u / h0)
    };
    let a2 = p1 + (p2 - p1) * (u / h1);
    let a3 = if h2 == 0.0 {
        p2
    } else {
        p2 + (p3 - p2) * ((u - h1) / h2)
    };
    let b1 = (a1 * (h1 - u) + a2 * (u + h0)) / (h0 + h1);
    let b2 = (a2 * (h1 + h2 - u) + a3 * u) / (h1 + h2);
    (b1 * (h1 - u) + b2 * u) / h1
}
