//! Colour science for eyeadapt: colour spaces, chromatic adaptation, and the
//! adaptation-colour estimators the paper compares against (Gruson, Ribardière
//! & Cozot 2013; specification in `shared/design/estimators.md`).
//!
//! Colours are `glam::DVec3` in scene-linear sRGB or CIE XYZ ([`rgb_to_xyz`]
//! and friends convert, with [`D65_XYZ`] as the display white). An estimator reads a
//! frame's [`FrameAovs`] and returns an [`Estimate`] — an absolute XYZ white
//! plus flags; [`adaptation_matrix_rgb`] turns that white into the per-frame
//! 3×3 transform for a chosen [`Cat`] and degree of adaptation (see
//! [`degree_of_adaptation`]). [`xyz_to_lab`], [`delta_e_2000`],
//! [`cct_mccamy`] and [`hsv_of_linear`] are the read-outs used in logs and metrics.
//!
//! The temporal side: coherence metrics of a per-frame adaptation-colour series
//! ([`series_metrics`](fn@series_metrics)) and of the adapted image sequence ([`image_metrics`](fn@image_metrics)), and a causal
//! filter modelling how fast the eye re-adapts ([`TemporalFilter`], run by [`AdaptationFilter`]).

mod cat;
mod cct;
mod degree;
mod estimators;
mod hsv;
mod image_metrics;
mod lab;
mod series_metrics;
mod spaces;
mod temporal_filter;

pub use crate::{
    cat::{Cat, UnknownCat, adaptation_matrix_rgb, adaptation_matrix_xyz},
    cct::{CCT_RANGE_K, cct_mccamy, cct_mccamy_xyz},
    degree::{DegreeModel, L_A_SRGB, Surround, degree_cie97s, degree_of_adaptation},
    estimators::*,
    hsv::{Hsv, hsv, hsv_of_8bit, hsv_of_linear},
    image_metrics::{
        DEFAULT_DE_THRESHOLD, DEFAULT_STRIDE, DEFAULT_Y_PERCENTILE, FrameImageMetrics,
        GREY_REFLECTANCE, ImageMetrics, ImageMetricsAccumulator, ImageMetricsParams, LabConverter,
        LabImage, LuminancePercentile, PixelSubset, SequenceFrame, SeriesSummary, delta_e_cat_grey,
        image_metrics, image_metrics_summary, mean_delta_e, sequence_y_n,
    },
    lab::{HUE_BRANCH_TOLERANCE_DEG, delta_e_2000, xyz_to_lab},
    series_metrics::{
        DEFAULT_SIGMA_S, DEFAULT_THRESHOLDS, JumpCount, MAX_SIGMA_FRAMES, MetricRow, SeriesError,
        SeriesMetrics, SeriesParams, SeriesPoint, series_metrics,
    },
    spaces::{
        D65_XY, D65_XYZ, M_RGB_TO_XYZ, M_XYZ_TO_RGB, delta_uv, luminance, luminance_f32,
        rgb_to_xyz, srgb_decode, srgb_encode, xy_to_uv, xy_to_xyz, xyz_to_rgb, xyz_to_uv,
        xyz_to_xy,
    },
};
pub use temporal_filter::{
    AdaptationFilter, FilterError, FilterFlags, FilterInit, FilterOutput, FilterParams,
    TemporalFilter, filter_series, smoothing_factor,
};
