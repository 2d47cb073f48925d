//! The six test cases: their job files (embedded) and quick-variant sizes.

/// One test case of the paper.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CaseInfo {
    pub number: u32,
    /// File-name stem of the contact sheet and work directory.
    pub slug: &'static str,
    pub title: &'static str,
    /// The paper's figures.
    pub figures: &'static str,
    /// Job files (embedded `configs/<name>.toml`), rendered in this order.
    pub jobs: &'static [(&'static str, &'static str)],
    /// Quick variant: (width, height, spp) per job.
    pub quick: &'static [(u32, u32, u32)],
}

/// The six cases of [GRC13] §5.
pub const CASES: &[CaseInfo] = &[
    CaseInfo {
        number: 1,
        slug: "case1-cornell-orange",
        title: "White Cornell box, orange light",
        figures: "Fig. 5",
        jobs: &[(
            "cornell-orange",
            include_str!("../../../configs/cornell-orange.toml"),
        )],
        quick: &[(64, 64, 16)],
    },
    CaseInfo {
        number: 2,
        slug: "case2-one-reflectance",
        title: "Worlds of one reflectance",
        figures: "Fig. 6, 7",
        jobs: &[
            (
                "white-world-orange-light",
                include_str!("../../../configs/white-world-orange-light.toml"),
            ),
            (
                "orange-world-white-light",
                include_str!("../../../configs/orange-world-white-light.toml"),
            ),
        ],
        quick: &[(64, 48, 16), (64, 48, 16)],
    },
    CaseInfo {
        number: 3,
        slug: "case3-cornell-green-floor",
        title: "Cornell box with a green floor, white light, colour checker",
        figures: "Fig. 8",
        jobs: &[(
            "cornell-green-floor",
            include_str!("../../../configs/cornell-green-floor.toml"),
        )],
        quick: &[(128, 128, 16)],
    },
    CaseInfo {
        number: 4,
        slug: "case4-statue-red-spot",
        title: "White statue, red spot light, white ceiling light",
        figures: "Fig. 9",
        jobs: &[(
            "statue-red-spot",
            include_str!("../../../configs/statue-red-spot.toml"),
        )],
        quick: &[(128, 96, 64)],
    },
    CaseInfo {
        number: 5,
        slug: "case5-two-rooms",
        title: "Two rooms (orange, blue), three views",
        figures: "Fig. 10-12",
        jobs: &[("two-rooms", include_str!("../../../configs/two-rooms.toml"))],
        quick: &[(96, 72, 16)],
    },
    CaseInfo {
        number: 6,
        slug: "case6-three-rooms",
        title: "Three-room walkthrough (white, orange, blue)",
        figures: "Fig. 13-15",
        jobs: &[(
            "three-rooms",
            include_str!("../../../configs/three-rooms.toml"),
        )],
        quick: &[(96, 54, 4)],
    },
];
