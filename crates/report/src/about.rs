//! What each estimator measures, in one sentence, for the report's page (the definitions are
//! estimators.md §1–§5; the numbers in them are the defaults of §10).

/// One sentence on what `base` measures; `None` for an estimator this build does not know.
pub fn what_it_measures(base: &str) -> Option<&'static str> {
    Some(match base {
        "eye" => {
            "the light arriving at the eye: irradiance on a small hemisphere facing the gaze, from inside and outside the field of view (the paper's sensor)."
        }
        "eye_fov" => {
            "the same sensor restricted to the camera's field of view: what eye would read without the light from outside the frame."
        }
        "wcam" => {
            "the average colour of the light on the visible surfaces, white surfaces weighted up (Wilkie & Weidlich 2009)."
        }
        "ncns" => {
            "the colour of the light on the visible white surfaces, weighted towards the centre of the view (Neumann et al. 2003)."
        }
        "dominant" => {
            "the brightest light's colour — constant unless the brightest light changes (Ward & Eydelberg-Vileshin 2002; brightest by luminous flux)."
        }
        "grey_world" => "the mean colour of the frame: it assumes the world averages to grey.",
        "white_patch" => "the mean colour of the brightest pixels of the frame (the top 1 %).",
        "shades_of_grey" => {
            "a Minkowski 6-norm of the frame's colours: between grey world and white patch (Finlayson & Trezzi 2004)."
        }
        "grey_edge" => {
            "a 6-norm of the frame's colour edges: it assumes edges average to grey (van de Weijer et al. 2007)."
        }
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_estimator_of_the_sequencer_is_explained() {
        for e in eyeadapt_sequencer::Estimator::ALL.map(|e| e.name()) {
            assert!(what_it_measures(e).is_some(), "{e} has no sentence");
        }
        assert!(
            what_it_measures("dominant")
                .unwrap()
                .contains("constant unless the brightest light changes")
        );
    }
}
