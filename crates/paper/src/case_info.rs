//! The six test cases: their job files and scene templates (embedded) and the sizes of the
//! quick variant and of the sensitivity runs.

/// One test case of the paper.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CaseInfo {
    pub number: u32,
    /// File-name stem of the contact sheet and work directory.
    pub slug: &'static str,
    pub title: &'static str,
    /// The paper's figures.
    pub figures: &'static str,
    /// Jobs, rendered in this order: (name, job text, scene template), all of `paper/scenes/`;
    /// each job is a template filled with a configuration of the sensitivity study. Without a
    /// scene template the job names a built-in scene (its baseline is `configs/<name>.toml`);
    /// with one it reads `scene.toml`, the template filled likewise.
    pub jobs: &'static [Job],
    /// Files the scene template reads, written beside it (path relative to it, contents).
    pub files: &'static [(&'static str, &'static [u8])],
    /// Quick variant, and the full variant's sensitivity runs: (width, height, spp) per job.
    pub quick: &'static [(u32, u32, u32)],
    pub study: &'static [(u32, u32, u32)],
    /// The full variant's main run, when smaller than the jobs' own sizes (`None`: the jobs').
    pub full: Option<&'static [(u32, u32, u32)]>,
    /// Eye-sensor paths per frame in the quick variant (the full one uses the job's).
    pub quick_eye: u32,
    /// Eye-sensor paths per frame in the full variant's study runs (`None`: the job's).
    pub study_eye: Option<u32>,
}

/// (name, job text, scene template).
pub type Job = (&'static str, &'static str, Option<&'static str>);

/// The six cases of \[GRC13\] §5.
pub const CASES: &[CaseInfo] = &[
    CaseInfo {
        number: 1,
        slug: "case1-cornell-orange",
        title: "White Cornell box, orange light",
        figures: "Fig. 5",
        jobs: &[(
            "cornell-orange",
            include_str!("../../../paper/scenes/case1.job.toml"),
            None,
        )],
        files: &[],
        quick: &[(64, 64, 16)],
        study: &[(64, 64, 16)],
        full: None,
        quick_eye: 4096,
        study_eye: None,
    },
    CaseInfo {
        number: 2,
        slug: "case2-one-reflectance",
        title: "Worlds of one reflectance",
        figures: "Fig. 6, 7",
        jobs: &[
            (
                "white-world-orange-light",
                include_str!("../../../paper/scenes/case2-white-world-orange-light.job.toml"),
                None,
            ),
            (
                "orange-world-white-light",
                include_str!("../../../paper/scenes/case2-orange-world-white-light.job.toml"),
                None,
            ),
        ],
        files: &[],
        quick: &[(64, 48, 16), (64, 48, 16)],
        study: &[(64, 48, 16), (64, 48, 16)],
        full: None,
        quick_eye: 4096,
        study_eye: None,
    },
    CaseInfo {
        number: 3,
        slug: "case3-cornell-green-floor",
        title: "Cornell box with a green floor, white light, colour checker",
        figures: "Fig. 8",
        jobs: &[(
            "cornell-green-floor",
            include_str!("../../../paper/scenes/case3.job.toml"),
            Some(include_str!(
                "../../../paper/scenes/case3-cornell-green-floor.toml"
            )),
        )],
        files: &[],
        quick: &[(128, 128, 8)],
        study: &[(128, 128, 8)],
        full: None,
        quick_eye: 4096,
        study_eye: None,
    },
    CaseInfo {
        number: 4,
        slug: "case4-statue-red-spot",
        title: "White statue, red spot light, white ceiling light",
        figures: "Fig. 9",
        jobs: &[(
            "statue-red-spot",
            include_str!("../../../paper/scenes/case4.job.toml"),
            Some(include_str!(
                "../../../paper/scenes/case4-statue-red-spot.toml"
            )),
        )],
        files: &[(
            "meshes/guardian-lion.obj",
            include_bytes!("../../../paper/scenes/meshes/guardian-lion.obj"),
        )],
        quick: &[(96, 72, 16)],
        study: &[(96, 72, 16)],
        full: None,
        quick_eye: 4096,
        study_eye: None,
    },
    CaseInfo {
        number: 5,
        slug: "case5-two-rooms",
        title: "Two rooms (orange, blue), three views",
        figures: "Fig. 10-12",
        jobs: &[(
            "two-rooms",
            include_str!("../../../paper/scenes/case5.job.toml"),
            None,
        )],
        files: &[],
        quick: &[(96, 72, 16)],
        study: &[(96, 72, 16)],
        full: None,
        quick_eye: 4096,
        study_eye: None,
    },
    CaseInfo {
        number: 6,
        slug: "case6-three-rooms",
        title: "Three-room walkthrough (white, orange, blue)",
        figures: "Fig. 13-15",
        jobs: &[(
            "three-rooms",
            include_str!("../../../paper/scenes/case6.job.toml"),
            Some(include_str!("../../../paper/scenes/case6-three-rooms.toml")),
        )],
        files: &[],
        quick: &[(64, 36, 2)],
        // 121 frames: the full variant's main run at half the job's size, its study runs smaller
        // still, so that `eyeadapt paper` finishes in well under an hour on 2 busy cores. 8 spp
        // in the study: at 4 the bench's brightest pixel (the design check) is mostly noise.
        study: &[(48, 27, 8)],
        full: Some(&[(160, 90, 8)]),
        quick_eye: 2048,
        study_eye: Some(4096),
    },
];
