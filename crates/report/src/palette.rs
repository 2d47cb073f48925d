//! One colour per estimator, everywhere the report draws one (plots, page, legends), and the
//! line style of each temporal filter. `scripts/plot_adaptation.py` mirrors this table; a test
//! below checks that the two agree.
use plotters::style::RGBColor;

/// The estimators' colours (Tableau 10). The eye sensor is black, and drawn thickest.
pub const PALETTE: &[(&str, RGBColor)] = &[
    ("eye", RGBColor(0, 0, 0)),
    ("eye_fov", RGBColor(127, 127, 127)),
    ("wcam", RGBColor(225, 87, 89)),
    ("ncns", RGBColor(78, 121, 167)),
    ("dominant", RGBColor(176, 122, 161)),
    ("grey_world", RGBColor(89, 161, 79)),
    ("white_patch", RGBColor(242, 142, 43)),
    ("shades_of_grey", RGBColor(118, 183, 178)),
    ("grey_edge", RGBColor(156, 117, 95)),
];

/// Colour of an estimator (a filtered copy has its base estimator's colour). Any other name
/// gets a stable colour from its bytes.
pub fn colour_of(base: &str) -> RGBColor {
    if let Some((_, c)) = PALETTE.iter().find(|(n, _)| *n == base) {
        return *c;
    }
    let h = base
        .bytes()
        .fold(7u32, |h, b| h.wrapping_mul(31).wrapping_add(b as u32));
    RGBColor(
        (h % 200) as u8,
        ((h / 200) % 200) as u8,
        ((h / 40_000) % 200) as u8,
    )
}

/// Dash and gap lengths (pixels) of a filtered series' line; `None`: solid (per-frame
/// estimates). fairchild dashed, artistic dotted, rinner long dashes.
pub fn dash_of(filter: Option<&str>) -> Option<(u32, u32)> {
    match filter? {
        "fairchild" => Some((7, 4)),
        "artistic" => Some((2, 3)),
        _ => Some((12, 4)),
    }
}

/// `#rrggbb` of a colour, for the page's CSS.
pub fn hex(c: RGBColor) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plot_script_uses_the_same_colours() {
        let script = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scripts/plot_adaptation.py"
        ))
        .unwrap();
        let table = &script[script.find("PALETTE = {").expect("a PALETTE dict")..];
        let table = &table[..table.find('}').unwrap()];
        let entries: Vec<(String, String)> = table
            .lines()
            .filter_map(|l| {
                let (k, v) = l.trim().trim_end_matches(',').split_once(':')?;
                Some((
                    k.trim().trim_matches('"').into(),
                    v.trim().trim_matches('"').into(),
                ))
            })
            .collect();
        let ours: Vec<(String, String)> = PALETTE
            .iter()
            .map(|(n, c)| (n.to_string(), hex(*c)))
            .collect();
        assert_eq!(entries, ours);
        for style in [
            "\"fairchild\": \"--\"",
            "\"artistic\": \":\"",
            "\"rinner\": (0, (6, 2))",
        ] {
            assert!(script.contains(style), "script lacks {style}");
        }
    }

    #[test]
    fn every_estimator_has_its_own_colour() {
        for (i, (a, ca)) in PALETTE.iter().enumerate() {
            for (b, cb) in &PALETTE[i + 1..] {
                assert_ne!(ca, cb, "{a} and {b} share a colour");
            }
        }
        assert_eq!(colour_of("wcam"), RGBColor(225, 87, 89));
        assert_eq!(colour_of("somebody_else"), colour_of("somebody_else"));
        assert_eq!(dash_of(None), None);
        assert_ne!(dash_of(Some("fairchild")), dash_of(Some("artistic")));
    }
}
