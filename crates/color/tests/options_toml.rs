//! Options as a job file writes them: every key optional with the §10 default,
//! unknown keys rejected with a message that names them.

use eyeadapt_color::*;
use serde::Deserialize;

#[test]
fn empty_tables_give_the_spec_defaults() {
    let wcam: WcamOptions = toml::from_str("").unwrap();
    assert_eq!(
        (wcam.w, wcam.weight, wcam.achromatic),
        (2.0, WcamWeight::Linear, WcamAchromatic::Luminance)
    );
    assert_eq!(
        (wcam.specular, wcam.include_emitters, wcam.normalize_pixels),
        (WcamSpecular::Include, false, false)
    );
    let ncns: NcnsOptions = toml::from_str("").unwrap();
    assert_eq!(
        (ncns.white_min_luminance, ncns.white_max_saturation),
        (0.6, 0.1)
    );
    assert_eq!(
        (ncns.axis_weight, ncns.sigma_a_deg, ncns.cos_k),
        (AxisWeight::Gaussian, 15.0, 8.0)
    );
    assert!(ncns.solid_angle_weight);
    let sog: ShadesOfGreyOptions = toml::from_str("").unwrap();
    assert_eq!((sog.p, sog.sigma, sog.clip_percentile), (6.0, 0.0, None));
    let ge: GreyEdgeOptions = toml::from_str("").unwrap();
    assert_eq!(
        (ge.n, ge.p, ge.sigma, ge.clip_percentile),
        (1, 6.0, 1.0, None)
    );
    let wp: WhitePatchOptions = toml::from_str("").unwrap();
    assert_eq!(
        (wp.mode, wp.top_percent, wp.percentile),
        (WhitePatchMode::TopPercent, 1.0, 99.0)
    );
    let gw: GreyWorldOptions = toml::from_str("").unwrap();
    assert_eq!(gw.clip_percentile, None);
    let dom: DominantOptions = toml::from_str("").unwrap();
    assert_eq!(dom.by, DominantBy::Flux);
}

#[test]
fn every_variant_name_parses() {
    let w: WcamOptions =
        toml::from_str("weight = \"power\"\nachromatic = \"unit\"\nspecular = \"exclude_delta\"")
            .unwrap();
    assert_eq!(
        (w.weight, w.achromatic, w.specular),
        (
            WcamWeight::Power,
            WcamAchromatic::Unit,
            WcamSpecular::ExcludeDelta
        )
    );
    let w: WcamOptions = toml::from_str("specular = \"diffuse_only\"").unwrap();
    assert_eq!(w.specular, WcamSpecular::DiffuseOnly);
    let n: NcnsOptions =
        toml::from_str("axis_weight = \"cos_power\"\ncos_k = 4").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((n.axis_weight, n.cos_k), (AxisWeight::CosPower, 4.0));
    for (name, mode) in [
        ("top_percent", WhitePatchMode::TopPercent),
        (
            "per_channel_percentile",
            WhitePatchMode::PerChannelPercentile,
        ),
        ("max", WhitePatchMode::Max),
    ] {
        let wp: WhitePatchOptions = toml::from_str(&format!("mode = \"{name}\"")).unwrap();
        assert_eq!(wp.mode, mode);
    }
    let p: ShadesOfGreyOptions = toml::from_str("p = inf").unwrap();
    assert!(p.p.is_infinite() && p.validate().is_ok());
}

#[test]
fn unknown_keys_are_rejected_by_name() {
    let err = toml::from_str::<WcamOptions>("wieght = \"power\"")
        .unwrap_err()
        .to_string();
    assert!(err.contains("unknown field `wieght`"), "{err}");
    let err = toml::from_str::<GreyEdgeOptions>("order = 2")
        .unwrap_err()
        .to_string();
    assert!(err.contains("unknown field `order`"), "{err}");
    let err = toml::from_str::<WhitePatchOptions>("mode = \"brightest\"")
        .unwrap_err()
        .to_string();
    assert!(err.contains("unknown variant `brightest`"), "{err}");
}

#[test]
fn cat_surround_and_degree_model_from_job_files() {
    #[derive(Debug, Deserialize)]
    struct Adapt {
        cat: Cat,
        surround: Surround,
        d_model: DegreeModel,
    }
    let a: Adapt =
        toml::from_str("cat = \"vonkries\"\nsurround = \"dim\"\nd_model = \"cie97s\"").unwrap();
    assert_eq!(
        (a.cat, a.surround, a.d_model),
        (Cat::VonKries, Surround::Dim, DegreeModel::Cie97s)
    );
    let err = toml::from_str::<Adapt>("cat = \"cat97\"\nsurround = \"dim\"\nd_model = \"cie02\"")
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("expected one of `cat02`, `cat16`, `bradford`, `vonkries`"),
        "{err}"
    );
}
