//! The `<integrator>`: `path` and `direct`, and the wrappers and relatives eyeadapt renders
//! with its path tracer (`moment`, `aov`, `ptracer`, and `volpath` in a scene without media),
//! each with a warning at its element.
use super::Builder;
use crate::CutoutShadows;
use crate::mitsuba::xml::Obj;

impl<'t> Builder<'t> {
    pub(super) fn integrator(&mut self, o: &'t Obj) {
        match o.kind.as_str() {
            // Both add AOVs to the image of the integrator they nest.
            "moment" | "aov" => {
                self.warning(
                    o.at,
                    format!(
                        "{}: eyeadapt renders its nested integrator's image; the extra AOVs are not written",
                        o.describe()
                    ),
                );
                // `aov`'s list of AOVs, accepted.
                if o.kind == "aov" {
                    self.string(o, "aovs");
                }
                match self.nested(o, "integrator") {
                    Some(inner) => self.integrator(inner),
                    None => self.error(
                        o.at,
                        format!("{} needs one nested <integrator>", o.describe()),
                    ),
                }
                self.finish(o);
            }
            "ptracer" => {
                self.warning(
                    o.at,
                    format!(
                        "{}: eyeadapt traces from the camera (its path integrator); the image converges to the same",
                        o.describe()
                    ),
                );
                self.path(o);
            }
            "path" => self.path(o),
            // Without media Mitsuba's volpath computes what path does (its surface
            // interactions are path's: BSDF sampling, emitter sampling, MIS, roulette), except
            // that its shadow rays pass masks' holes and null surfaces and crossing one is not
            // a segment.
            "volpath" if !self.has_media => {
                self.warning(
                    o.at,
                    format!(
                        "{}: the scene has no participating media, so eyeadapt renders it with its path integrator, shadow rays passing masks and null surfaces (the same image)",
                        o.describe()
                    ),
                );
                self.path(o);
                self.scene.cutout_shadows = CutoutShadows::Transmit;
            }
            "volpath" => self.error(
                o.at,
                format!(
                    "unsupported {} with participating media: eyeadapt has no media",
                    o.describe()
                ),
            ),
            "direct" => self.direct(o),
            _ => self.error(
                o.at,
                format!(
                    "unsupported {}: eyeadapt renders the path and direct integrators (and moment, aov, ptracer and, without media, volpath as path)",
                    o.describe()
                ),
            ),
        }
    }

    /// `max_depth`, `rr_depth` and `hide_emitters` of `path` (and `ptracer`).
    fn path(&mut self, o: &'t Obj) {
        match self.int(o, "max_depth") {
            Some((d, _)) if d == -1 || (1..=1024).contains(&d) => {
                self.scene.render.max_depth = Some(d as i32)
            }
            Some((d, at)) => self.error(
                at,
                format!(
                    "{}: max_depth {d} must be -1 (unlimited) or 1..=1024",
                    o.describe()
                ),
            ),
            None => self.scene.render.max_depth = Some(-1),
        }
        match self.int(o, "rr_depth") {
            Some((d, _)) if (1..=1024).contains(&d) => self.scene.render.rr_depth = Some(d as u32),
            Some((d, at)) => self.error(
                at,
                format!("{}: rr_depth {d} must be 1..=1024", o.describe()),
            ),
            None => self.scene.render.rr_depth = Some(5),
        }
        // Accepted: how many samples Mitsuba takes per pass changes nothing in the result.
        self.int(o, "samples_per_pass");
        self.visible_emitters(o);
        self.finish(o);
    }

    /// `direct`: emitters seen directly plus direct lighting, i.e. paths of at most two
    /// segments. Mitsuba splits each sample into `emitter_samples` light samples and
    /// `bsdf_samples` BSDF samples combined by MIS; eyeadapt takes one of each per sample,
    /// which converges to the same image (only the noise differs) unless a count of 0 turns off
    /// the only strategy that sees some light.
    fn direct(&mut self, o: &'t Obj) {
        self.scene.render.max_depth = Some(2);
        let mut counts = [1i64; 2];
        for (k, name) in ["emitter_samples", "bsdf_samples"].into_iter().enumerate() {
            match self.int(o, name) {
                Some((n, _)) if (0..=1 << 16).contains(&n) => counts[k] = n,
                Some((n, at)) => self.error(
                    at,
                    format!("{}: {name} {n} must be 0..=65536", o.describe()),
                ),
                None => {}
            }
        }
        // Mitsuba's `shading_samples` sets both counts that are not given.
        if let Some((n, at)) = self.int(o, "shading_samples")
            && !(1..=1 << 16).contains(&n)
        {
            self.error(
                at,
                format!("{}: shading_samples {n} must be 1..=65536", o.describe()),
            );
        }
        if counts.contains(&0) {
            let off = if counts[0] == 0 { "emitter" } else { "BSDF" };
            self.warning(
                o.at,
                format!(
                    "{}: eyeadapt keeps {off} sampling on (it takes one light and one BSDF sample per pixel sample); the image is the same unless only that strategy reaches some light ({})",
                    o.describe(),
                    if counts[0] == 0 {
                        "point, spot and directional lights are seen by emitter sampling alone"
                    } else {
                        "lights seen only in mirrors or through glass need BSDF sampling"
                    }
                ),
            );
        }
        self.visible_emitters(o);
        self.finish(o);
    }

    /// `hide_emitters`: only `false` (Mitsuba's default) is supported.
    fn visible_emitters(&mut self, o: &'t Obj) {
        if let Some(true) = self.boolean(o, "hide_emitters") {
            let at = self.prop(o, "hide_emitters").map_or(o.at, |p| p.at);
            self.error(
                at,
                format!("{}: hide_emitters = true is not supported", o.describe()),
            );
        }
    }
}
