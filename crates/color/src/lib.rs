//! Colour science for eye adaptation: estimators of the adaptation white, chromatic adaptation
//! transforms, and the temporal side — coherence metrics of a per-frame adaptation-colour
//! series ([`series_metrics`]) and a causal filter modelling how fast the eye re-adapts
//! ([`TemporalFilter`], run by [`AdaptationFilter`]).

mod series_metrics;
mod temporal_filter;

pub use series_metrics::{
    DEFAULT_SIGMA_S, DEFAULT_THRESHOLDS, JumpCount, MetricRow, SeriesError, SeriesMetrics,
    SeriesParams, SeriesPoint, series_metrics,
};
pub use temporal_filter::{
    AdaptationFilter, FilterError, FilterFlags, FilterInit, FilterOutput, FilterParams,
    TemporalFilter, filter_series, smoothing_factor,
};
