//! Adaptation-colour estimators that work on a rendered frame's buffers
//! (estimators.md §2–§5). The paper's own eye sensor (§1) traces rays and lives
//! in the tracer.
//!
//! Each estimator is a free function `fn(&FrameAovs, &Options) -> Estimate`
//! (`dominant` takes the scene's light powers instead). Options structs
//! deserialise from job files with `deny_unknown_fields`, and their `Default`
//! is the §10 defaults. Every reduction is a sequential `f64` loop in pixel
//! order, so results never depend on the thread count.

mod dominant;
mod estimate;
mod frame;
mod gaussian;
mod masked_image;
mod minkowski;
mod ncns;
mod wcam;
mod white_patch;

pub use dominant::{DominantBy, DominantOptions, LightPower, dominant, dominant_light_index};
pub use estimate::{Estimate, flags};
pub use frame::FrameAovs;
pub use minkowski::{
    GreyEdgeOptions, GreyWorldOptions, MinkowskiParams, ShadesOfGreyOptions, grey_edge, grey_world,
    minkowski, shades_of_grey,
};
pub use ncns::{AxisWeight, NcnsOptions, ncns};
pub use wcam::{
    WcamAchromatic, WcamOptions, WcamSpecular, WcamWeight, albedo_saturation, wcam, whiteness,
};
pub use white_patch::{WhitePatchMode, WhitePatchOptions, white_patch};
