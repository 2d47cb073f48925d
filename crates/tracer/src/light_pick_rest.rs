//! The units of a spatial light choice ([`LightPicker`](super::LightPicker)) after its area
//! units — delta lights and the environment — flattened for the importance every path vertex
//! asks for: one small enum instead of [`Bounds`] around [`DeltaLight`], and what does not
//! depend on the shading point (a directional light's weight luminance, the environment's
//! irradiance) computed once.
//!
//! Every weight is bit for bit [`unit_importance`]'s: the same operations in the same order
//! on the same values (the test below holds them to it).
use super::{BEHIND_PORTALS, Behind, Bounds, unit_importance, weight_luminance};
use crate::emitter::DeltaLight;
use glam::Vec3A;
use std::f32::consts::PI;

#[derive(Clone, Copy, Debug)]
enum Rest {
    /// A directional light: the direction towards it, its irradiance's weight luminance, and
    /// whether that irradiance has no positive channel (weight 0 everywhere).
    Sun {
        wi: Vec3A,
        luminance: f32,
        dark: bool,
    },
    Point {
        position: Vec3A,
        intensity: Vec3A,
    },
    /// The environment's importance with a normal and without one.
    Env {
        lit: f32,
        all_round: f32,
    },
    Other(Bounds),
}

/// The units after the area units, in their order.
#[derive(Clone, Debug, Default)]
pub(super) struct Rests(Vec<Rest>);

impl Rests {
    /// `bounds`, which must hold no area unit.
    pub(super) fn new(bounds: &[Bounds]) -> Rests {
        Rests(Vec::from_iter(bounds.iter().map(|b| match *b {
            Bounds::Delta(DeltaLight::Directional {
                direction,
                irradiance,
            }) => Rest::Sun {
                wi: -direction,
                luminance: weight_luminance(irradiance),
                dark: irradiance.max_element() <= 0.0,
            },
            Bounds::Delta(DeltaLight::Point {
                position,
                intensity,
            }) => Rest::Point {
                position,
                intensity,
            },
            Bounds::Env { luminance } => Rest::Env {
                lit: PI * luminance,
                all_round: 4.0 * PI * luminance,
            },
            Bounds::Area(_) => panic!("an area unit after the area units"),
            other => Rest::Other(other),
        })))
    }

    /// Their importances at (`x`, `n`) into `w` (one per unit): [`unit_importance`]'s.
    #[inline]
    pub(super) fn importances(
        &self,
        x: Vec3A,
        n: Option<Vec3A>,
        behind: Option<Behind>,
        w: &mut [f32],
    ) {
        for (wk, r) in w.iter_mut().zip(&self.0) {
            *wk = importance(r, x, n, behind);
        }
    }
}

#[inline(always)]
fn importance(r: &Rest, x: Vec3A, n: Option<Vec3A>, behind: Option<Behind>) -> f32 {
    match *r {
        // `importance` of its arrival (wi = −direction, li = the irradiance), then
        // `unit_importance`'s portal factor (a weight of 0 keeps its bits under it).
        Rest::Sun {
            wi,
            luminance,
            dark,
        } => {
            let cos_r = match n {
                Some(n) => wi.dot(n),
                None => 1.0,
            };
            if cos_r <= 0.0 || dark {
                return 0.0;
            }
            let w = luminance * cos_r;
            match behind {
                Some(at) if at.portals.lets_through(x, wi) == Some(false) => w * BEHIND_PORTALS,
                _ => w,
            }
        }
        // `DeltaLight::arrival` and `importance`'s delta arm.
        Rest::Point {
            position,
            intensity,
        } => {
            let d = position - x;
            let d2 = d.length_squared();
            let dist = d2.sqrt();
            if dist <= 0.0 {
                return 0.0;
            }
            let wi = d / dist;
            let li = intensity / d2;
            let cos_r = match n {
                Some(n) => wi.dot(n),
                None => 1.0,
            };
            if cos_r <= 0.0 || li.max_element() <= 0.0 {
                return 0.0;
            }
            weight_luminance(li) * cos_r
        }
        Rest::Env { lit, all_round } => {
            let w = if n.is_some() { lit } else { all_round };
            match behind {
                Some(at) => w * at.sky,
                None => w,
            }
        }
        Rest::Other(ref b) => unit_importance(b, x, n, behind),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light_pick::LightPicker;
    use crate::portal::Portals;
    use eyeadapt_scene::Portal;
    use glam::Vec3;

    #[test]
    fn every_weight_is_the_one_unit_importance_bit_for_bit() {
        let lights = [
            DeltaLight::Directional {
                direction: Vec3A::new(0.7, -0.5, -0.25).normalize(),
                irradiance: Vec3A::new(7.0, 6.3, 5.4),
            },
            DeltaLight::Directional {
                direction: Vec3A::new(-0.2, -0.9, 0.1).normalize(),
                irradiance: Vec3A::ZERO,
            },
            DeltaLight::Point {
                position: Vec3A::new(1.2, 1.15, -2.2),
                intensity: Vec3A::new(1.6, 0.95, 0.38),
            },
            DeltaLight::Point {
                position: Vec3A::new(-1.0, 0.5, -4.0),
                intensity: Vec3A::new(0.0, 1e-30, 0.0),
            },
            DeltaLight::Spot {
                position: Vec3A::new(0.0, 2.5, -3.0),
                direction: -Vec3A::Y,
                intensity: Vec3A::ONE,
                cos_cone: 0.8,
                cos_falloff: 0.9,
                cone: 0.64,
                inv_transition: 10.0,
            },
        ];
        let picker = LightPicker::build(&[], &[], &[], &lights, Some(Vec3A::splat(0.4)), 8.0);
        let window = |z0: f32| Portal {
            corner: Vec3::new(-3.0, 0.7, z0),
            u: Vec3::new(0.0, 1.8, 0.0),
            v: Vec3::new(0.0, 0.0, 1.6),
        };
        let portals = Portals::new(&[window(-5.0), window(-2.4)]);
        let rests = Rests::new(&picker.bounds);
        let mut f = 0.137f32;
        let mut next = move || {
            f = (f * 97.31 + 0.2137).fract();
            f * 2.0 - 1.0
        };
        let DeltaLight::Directional { direction, .. } = lights[0] else {
            unreachable!()
        };
        let sun = -direction;
        let (mut cases, mut blocked, mut through) = (0, 0, 0);
        for i in 0..2000 {
            let x = Vec3A::new(next() * 4.0, next() * 3.0 + 1.0, next() * 4.0 - 3.0);
            let x = if i == 0 {
                Vec3A::new(1.2, 1.15, -2.2)
            } else {
                x
            };
            let n = Vec3A::new(next(), next(), next()).normalize_or(Vec3A::Y);
            for n in [None, Some(n), Some(-n), Some(Vec3A::X), Some(Vec3A::Y)] {
                for behind in [
                    None,
                    Some(Behind {
                        portals: &portals,
                        sky: portals.sky_share(x),
                    }),
                ] {
                    let mut w = [f32::NAN; 8];
                    rests.importances(x, n, behind, &mut w);
                    if let Some(at) = behind {
                        // The lit sun, held back where its direction crosses no portal.
                        blocked +=
                            (w[0] > 0.0 && at.portals.lets_through(x, sun) == Some(false)) as u32;
                        through +=
                            (w[0] > 0.0 && at.portals.lets_through(x, sun) == Some(true)) as u32;
                    }
                    for (k, b) in picker.bounds.iter().enumerate() {
                        let one = unit_importance(b, x, n, behind);
                        assert_eq!(w[k].to_bits(), one.to_bits(), "unit {k} at {x} n {n:?}");
                    }
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 20_000);
        // Both portal cases of the sun's weight were compared, not only the unserved one.
        assert!(
            blocked > 100 && through > 100,
            "{blocked} blocked, {through} through"
        );
    }
}
