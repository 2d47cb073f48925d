//! RESULTS.md: the paper's claims, the measured numbers, the verdicts, and — where a claim does
//! not reproduce — what was investigated. Deterministic: no timestamps, timings or paths that
//! depend on the machine.
use super::{CaseReport, PaperOptions, variant_description};
use std::fmt::Write;
use std::path::Path;

/// Investigation notes, shown under a case when the named claim does not hold. Written after
/// looking at the full run; they explain, they do not excuse (the scenes were not tuned).
fn failure_note(case: u32, claim_index: usize) -> Option<&'static str> {
    match (case, claim_index) {
        (3, 1) => Some(
            "The eye sensor reads a white that is greener than the light the wall above the checker receives \
             (compare the columns \"Δu′v′ to D65\" and \"Δu′v′ to the wall's irradiance\"), so it over-corrects \
             like WCAM and the two whites nearly coincide. The camera and its sensor sit in front of the open box; \
             the cardioid gives the bright green floor, which fills the lower part of the view, a weight close to \
             1, while the back wall receives the floor's light at grazing angles. `eye_fov` equals `eye` here: \
             the box opens onto a black void, so the part of the sensor outside the field of view has nothing to \
             add. The paper's 132°/2 % needs a sensor reading less green than the wall's irradiance, i.e. more \
             neutral light reaching the eye from outside the view (a closed box, white walls behind the camera) \
             or another camera position; the paper gives neither, and the scene was not changed to find out.",
        ),
        (3, 2) => Some(
            "The eye and WCAM whites nearly coincide (see above), so their adapted checkers differ by about 0.1 \
             ΔE00 or less. The error both leave (about 5 ΔE00, largest on the light patches) is the green cast on \
             the lower back wall where the checker hangs, stronger than on the wall above it: one white cannot \
             remove a cast that varies across the image.",
        ),
        (4, 1) => Some(
            "The statue's unlit side is not lit by white light alone. The spot's 18° beam is wider than the \
             statue, and the red light it throws on the back wall, floor and pedestal reflects onto the statue's \
             far side, whose irradiance (above) is about as red as WCAM's white. So WCAM renders that side \
             neutral (hue 180° at a saturation this low is a trace of cyan), not blue. The claim needs the unlit \
             side to receive less red than WCAM's white; the paper's spot was presumably tighter. The scene was \
             not changed after measuring.",
        ),
        (4, 2) => Some(
            "`eye` integrates the whole, mostly white-lit room, so its white stays close to D65 (the less biased \
             estimate by Δu′v′) and it leaves both sides of the statue as red as they are physically lit — the \
             lit side directly, the unlit side through the red interreflection described above. The measurable \
             proxy for \"more natural\" used here (a less saturated white surface on the unlit side) therefore \
             favours WCAM in this scene.",
        ),
        (6, 2) => Some(
            "The diagnostic `wcam_without_bench` is the test of the paper's explanation: with no highlight of a \
             light in view on the bench (see the previous note), leaving the bench out changes WCAM's white by \
             far less than a just-noticeable difference.",
        ),
        (6, 1) => Some(
            "In this walkthrough (`scenes/three-rooms`) no specular highlight of a light shows on the bench \
             during the first second: the bench's pixels carry a few percent at most of WCAM's weighted sum, and \
             leaving them out moves WCAM's white by a small fraction of a just-noticeable difference. From the \
             early camera path the ceiling light's mirror direction on the bench is out of view, and a highlight \
             of the white light among white-lit walls would barely move WCAM's chromaticity anyway. WCAM's large \
             steps come instead where the view changes colour quickly: approaching a doorway (room 1's largest \
             step) and crossing into room 3 (the largest overall). WCAM as reconstructed averages radiance, so a \
             bright highlight of a differently coloured light would dominate it as the paper describes; this \
             scene simply does not exercise that case, and it was not changed after measuring.",
        ),
        _ => None,
    }
}

/// Notes shown under a case whatever the outcome.
fn case_note(case: u32) -> Option<&'static str> {
    match case {
        2 => Some(
            "The image-only baselines cannot tell the two worlds apart — their raw images differ only through \
             interreflections — so they neutralise the orange world too: the \"world of one reflectance\" failure \
             of colour constancy that [GRC13] §3 cites (Ruppertsberg & Bloj 2007). `eye_fov`, which sees the same \
             walls but not the ceiling lamp, fails the same way: here it is light from outside the field of view \
             that tells the full sensor what the illuminant is. `wcam` reads the illumination through its \
             achromatic re-render; `ncns` is undefined in the orange world (no white surface) and falls back to \
             D65.",
        ),
        4 => Some(
            "The renderer picks lights for next-event estimation in proportion to their luminous power, so the \
             saturated red spot (low luminance) is chosen for about 2 % of the shadow rays and its light is \
             noisy at low sample counts; region means average that noise out, the previews show it as speckle.",
        ),
        _ => None,
    }
}

fn relative_link(results: &Path, out: &Path, file: &str) -> String {
    let target = out.join(file);
    match (results.parent(), target.parent()) {
        (Some(a), Some(b)) if a == b => file.to_string(),
        _ => target.display().to_string(),
    }
}

/// The whole of RESULTS.md.
pub fn results_markdown(o: &PaperOptions, reports: &[CaseReport]) -> String {
    let mut s = String::new();
    s.push_str("# Reproducing the claims of Gruson, Ribardière & Cozot 2013 (§5)\n\n");
    let _ = writeln!(
        s,
        "Generated by `eyeadapt paper`; do not edit (rerun it). {}. The same seed gives the same file, byte for byte. \
         How every number is measured: `docs/paper.md`. Scenes: `scenes/`, jobs: `configs/`.\n",
        capitalise(&variant_description(o))
    );
    s.push_str(
        "Conventions. Chromaticity differences are Euclidean in CIE 1976 u′v′ (Δu′v′; 0.004 ≈ a just-noticeable \
         difference on a display, estimators.md §7.1). Adapted colours use CAT02 towards D65 with D = 1, as in the paper. \
         HSV is read on sRGB-encoded values after scaling the colour to the luminance of the surface's true reflectance \
         (estimators.md §6.9). `wcam` and `ncns` are reconstructions of methods whose full text could not be read \
         (estimators.md §2.2, §3); `eye_fov` is the eye sensor restricted to the field of view (an ablation, §1.5). \
         Contact sheets: one row per view, columns raw | WCAM | eye.\n\n",
    );
    s.push_str("## Summary\n\n| case | claim | holds |\n|---|---|---|\n");
    for r in reports {
        for v in &r.verdicts {
            let _ = writeln!(
                s,
                "| {} {} | {} | {} |",
                r.info.number,
                r.info.figures,
                v.claim,
                if v.holds { "yes" } else { "**no**" }
            );
        }
    }
    s.push('\n');
    let results = o.results_path();
    for r in reports {
        let _ = writeln!(
            s,
            "## Case {}: {} ({})\n",
            r.info.number, r.info.title, r.info.figures
        );
        let _ = writeln!(s, "**Paper.** {}\n", r.paper_claim);
        s.push_str(&r.markdown);
        s.push_str("\n**Verdicts.**\n\n");
        for v in &r.verdicts {
            let _ = writeln!(
                s,
                "- {} — {}: {}.",
                if v.holds {
                    "holds"
                } else {
                    "**does not hold**"
                },
                v.claim,
                v.test
            );
        }
        s.push('\n');
        for (i, v) in r.verdicts.iter().enumerate() {
            if !v.holds
                && let Some(n) = failure_note(r.info.number, i)
            {
                let _ = writeln!(s, "*Why \"{}\" does not hold.* {n}\n", v.claim);
            }
        }
        if let Some(n) = case_note(r.info.number) {
            let _ = writeln!(s, "*Note.* {n}\n");
        }
        if let Some(sheet) = &r.sheet {
            let _ = writeln!(
                s,
                "![case {} contact sheet: raw | WCAM | eye]({})\n",
                r.info.number,
                relative_link(&results, &o.out, sheet)
            );
        }
    }
    s
}

fn capitalise(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().collect::<String>() + c.as_str(),
        None => String::new(),
    }
}
