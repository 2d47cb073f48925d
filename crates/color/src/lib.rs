//! Colour science for eye adaptation: estimators of the adaptation white, chromatic adaptation
//! transforms, and the temporal side — coherence metrics of a per-frame adaptation-colour
//! series ([`series_metrics`]).

mod series_metrics;

pub use series_metrics::{
    DEFAULT_SIGMA_S, DEFAULT_THRESHOLDS, JumpCount, MetricRow, SeriesError, SeriesMetrics,
    SeriesParams, SeriesPoint, series_metrics,
};
