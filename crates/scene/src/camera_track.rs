//! Camera tracks from CSV files, for tools that export a camera as a table of poses.
//!
//! ```text
//! # comment lines start with '#'
//! time,x,y,z,qx,qy,qz,qw,fov_deg
//! 0.0,1.0,1.6,-2.0,0,0.7071068,0,0.7071068,45
//! 0.5,2.0,1.6,-2.0,0,0.6087614,0,0.7933533,45
//! ```
//!
//! - One row per pose, with a header naming the columns (any order). `time` (seconds) or
//!   `frame` (a frame number, at the job's fps: frame f is time f/fps);
//! - the position `x,y,z`;
//! - the orientation as a unit quaternion `qx,qy,qz,qw` taking the camera's own frame (looking
//!   along −z with +y up, glTF's and Blender's camera convention) to the world, **or** a look-at
//!   point `look_x,look_y,look_z` with an optional `up_x,up_y,up_z` (default +y);
//! - optionally `fov_deg`, the vertical field of view (otherwise the scene camera's).
//!
//! Between rows the position and fov are interpolated linearly and the orientation by
//! shortest-path slerp (the rules of [`Track`] with LINEAR interpolation); before the first row
//! and after the last the end pose holds. A sequence's frame i is at time i/fps, as for glTF
//! animations, so a track exported one row per frame is reproduced exactly at its frames.
use crate::track::{Interpolation, Track};
use crate::{CameraPose, Diagnostic, SceneError, Severity};
use glam::{DQuat, DVec3};
use std::path::{Path, PathBuf};

/// Most rows a track may have (a day at 120 fps is about 10⁷).
pub const MAX_TRACK_ROWS: usize = 20_000_000;

/// A camera track read from a CSV file.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraTrack {
    pub source: PathBuf,
    pub position: Track<DVec3>,
    pub rotation: Track<DQuat>,
    /// Vertical field of view in degrees (as a vector with the value in x), if the file has it.
    pub fov_deg: Option<Track<DVec3>>,
}

impl CameraTrack {
    /// The camera at time `t` (seconds).
    pub fn pose(&self, t: f64) -> CameraPose {
        let q = self.rotation.sample(t);
        CameraPose {
            position: self.position.sample(t),
            forward: (q * DVec3::NEG_Z).normalize(),
            up: (q * DVec3::Y).normalize(),
            fov_deg: self.fov_deg.as_ref().map(|f| f.sample(t).x),
        }
    }

    /// First and last row times (seconds).
    pub fn range(&self) -> (f64, f64) {
        self.position.range()
    }

    /// Reads `path`; `fps` converts a `frame` column to seconds.
    pub fn read_csv(path: &Path, fps: f64) -> Result<CameraTrack, SceneError> {
        let err = |line: u64, message: String| SceneError {
            diagnostics: vec![Diagnostic {
                severity: Severity::Error,
                file: path.to_path_buf(),
                line: line as usize,
                col: usize::from(line > 0),
                message,
            }],
        };
        let file = crate::open_input(path)
            .map_err(|e| err(0, format!("cannot read camera track: {e}")))?;
        let mut reader = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .from_reader(file);
        let header_line = reader.position().line();
        let header = reader
            .headers()
            .map_err(|e| err(header_line, format!("cannot read the header: {e}")))?
            .clone();
        let cols = Columns::find(&header).map_err(|m| err(header_line.max(1), m))?;
        let mut rows = Rows::default();
        for record in reader.records() {
            let record = record.map_err(|e| {
                let line = e.position().map_or(0, |p| p.line());
                err(line, format!("not a CSV row: {e}"))
            })?;
            let line = record.position().map_or(0, |p| p.line());
            if rows.times.len() >= MAX_TRACK_ROWS {
                return Err(err(line, format!("more than {MAX_TRACK_ROWS} rows")));
            }
            cols.row(&record, &header, fps, &mut rows)
                .map_err(|m| err(line, m))?;
            if let [.., a, b] = rows.times[..]
                && b <= a
            {
                return Err(err(
                    line,
                    format!("times must increase strictly ({a} then {b})"),
                ));
            }
        }
        if rows.times.is_empty() {
            return Err(err(0, "the camera track has no rows".into()));
        }
        let (times, interpolation) = (rows.times, Interpolation::Linear);
        Ok(CameraTrack {
            source: path.to_path_buf(),
            position: Track {
                times: times.clone(),
                values: rows.positions,
                interpolation,
            },
            rotation: Track {
                times: times.clone(),
                values: rows.rotations,
                interpolation,
            },
            fov_deg: cols.fov.map(|_| Track {
                times,
                values: rows
                    .fovs
                    .into_iter()
                    .map(|f| DVec3::new(f, 0.0, 0.0))
                    .collect(),
                interpolation,
            }),
        })
    }
}

#[derive(Default)]
struct Rows {
    times: Vec<f64>,
    positions: Vec<DVec3>,
    rotations: Vec<DQuat>,
    fovs: Vec<f64>,
}

/// Where each quantity is in a row.
struct Columns {
    /// The `time` or `frame` column and whether it is frames.
    time: (usize, bool),
    position: [usize; 3],
    orientation: Orient,
    fov: Option<usize>,
}

enum Orient {
    Quat([usize; 4]),
    LookAt([usize; 3], Option<[usize; 3]>),
}

impl Columns {
    fn find(h: &csv::StringRecord) -> Result<Columns, String> {
        const KNOWN: [&str; 16] = [
            "time", "frame", "x", "y", "z", "qx", "qy", "qz", "qw", "look_x", "look_y", "look_z",
            "up_x", "up_y", "up_z", "fov_deg",
        ];
        if let Some(bad) = h.iter().find(|c| !KNOWN.contains(c)) {
            return Err(format!(
                "unknown column \"{bad}\" (known: time or frame, x,y,z, qx,qy,qz,qw or \
                 look_x,look_y,look_z [up_x,up_y,up_z], fov_deg)"
            ));
        }
        if let Some(dup) = h
            .iter()
            .enumerate()
            .find(|(i, c)| h.iter().skip(i + 1).any(|d| d == *c))
        {
            return Err(format!("column \"{}\" appears twice", dup.1));
        }
        let col = |name: &str| h.iter().position(|c| c == name);
        let all = |names: &[&str]| -> Option<Vec<usize>> { names.iter().map(|n| col(n)).collect() };
        let time = match (col("time"), col("frame")) {
            (Some(t), None) => (t, false),
            (None, Some(f)) => (f, true),
            (Some(_), Some(_)) => return Err("give `time` or `frame`, not both".into()),
            (None, None) => return Err("no `time` or `frame` column".into()),
        };
        let position = all(&["x", "y", "z"]).ok_or("the position needs columns x, y and z")?;
        let quat = all(&["qx", "qy", "qz", "qw"]);
        let look = all(&["look_x", "look_y", "look_z"]);
        let up = all(&["up_x", "up_y", "up_z"]);
        let orientation = match (quat, look) {
            (Some(q), None) => Orient::Quat([q[0], q[1], q[2], q[3]]),
            (None, Some(l)) => Orient::LookAt([l[0], l[1], l[2]], up.map(|u| [u[0], u[1], u[2]])),
            (Some(_), Some(_)) => {
                return Err("give a quaternion or a look-at point, not both".into());
            }
            (None, None) => {
                return Err(
                    "the orientation needs qx,qy,qz,qw or look_x,look_y,look_z columns".into(),
                );
            }
        };
        Ok(Columns {
            time,
            position: [position[0], position[1], position[2]],
            orientation,
            fov: col("fov_deg"),
        })
    }

    fn row(
        &self,
        r: &csv::StringRecord,
        h: &csv::StringRecord,
        fps: f64,
        out: &mut Rows,
    ) -> Result<(), String> {
        if r.len() != h.len() {
            return Err(format!(
                "{} fields where the header has {}",
                r.len(),
                h.len()
            ));
        }
        let num = |i: usize| -> Result<f64, String> {
            let v: f64 = r[i]
                .parse()
                .map_err(|_| format!("field `{}`: \"{}\" is not a number", &h[i], &r[i]))?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(format!("field `{}`: {v} is not finite", &h[i]))
            }
        };
        let v3 = |c: [usize; 3]| -> Result<DVec3, String> {
            Ok(DVec3::new(num(c[0])?, num(c[1])?, num(c[2])?))
        };
        let t = num(self.time.0)?;
        let t = if self.time.1 { t / fps } else { t };
        let position = v3(self.position)?;
        let rotation = match self.orientation {
            Orient::Quat(q) => {
                let q = DQuat::from_xyzw(num(q[0])?, num(q[1])?, num(q[2])?, num(q[3])?);
                if (q.length() - 1.0).abs() > 1e-3 {
                    return Err(format!("the quaternion has length {}, not 1", q.length()));
                }
                q.normalize()
            }
            Orient::LookAt(l, up) => {
                let up = match up {
                    Some(u) => v3(u)?,
                    None => DVec3::Y,
                };
                look_at(position, v3(l)?, up).ok_or(
                    "the look-at point equals the position or the up vector is parallel to the view",
                )?
            }
        };
        if let Some(c) = self.fov {
            let f = num(c)?;
            if !(f > 0.0 && f < 180.0) {
                return Err(format!("field `fov_deg`: {f} is not in (0, 180)"));
            }
            out.fovs.push(f);
        }
        out.times.push(t);
        out.positions.push(position);
        out.rotations.push(rotation);
        Ok(())
    }
}

/// The rotation taking the camera frame (−z forward, +y up) to look from `p` at `target`, on
/// the keyframe paths' own look-at basis.
fn look_at(p: DVec3, target: DVec3, up: DVec3) -> Option<DQuat> {
    let basis = crate::camera_path::orientation::look_at_basis(p, target, up)?;
    Some(DQuat::from_mat3(&basis).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(text: &str) -> (tempfile::TempDir, PathBuf) {
        let d = tempfile::tempdir().unwrap();
        let p = d.path().join("track.csv");
        std::fs::write(&p, text).unwrap();
        (d, p)
    }

    #[test]
    fn quaternion_rows_interpolate_and_hold_at_the_ends() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let (_d, p) = write(&format!(
            "# exported\ntime,x,y,z,qx,qy,qz,qw,fov_deg\n0,0,1.6,0,0,0,0,1,40\n2,4,1.6,0,0,{h},0,{h},50\n"
        ));
        let t = CameraTrack::read_csv(&p, 24.0).unwrap();
        let mid = t.pose(1.0);
        assert!((mid.position - DVec3::new(2.0, 1.6, 0.0)).length() < 1e-12);
        // Halfway between looking along −z and a 90° turn about +y (towards −x): 45°.
        let want = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_4) * DVec3::NEG_Z;
        assert!((mid.forward - want).length() < 1e-9, "{}", mid.forward);
        assert_eq!(mid.fov_deg, Some(45.0));
        assert_eq!(t.pose(-1.0).position, DVec3::new(0.0, 1.6, 0.0));
        assert_eq!(t.pose(9.0).position, DVec3::new(4.0, 1.6, 0.0));
        assert_eq!(t.range(), (0.0, 2.0));
    }

    #[test]
    fn frames_and_look_at_points() {
        let (_d, p) = write("frame,x,y,z,look_x,look_y,look_z\n0,0,0,0,1,0,0\n12,0,0,0,0,0,1\n");
        let t = CameraTrack::read_csv(&p, 24.0).unwrap();
        assert_eq!(t.range(), (0.0, 0.5));
        assert!((t.pose(0.0).forward - DVec3::X).length() < 1e-12);
        assert!((t.pose(0.5).forward - DVec3::Z).length() < 1e-12);
        assert!((t.pose(0.0).up - DVec3::Y).length() < 1e-12);
        assert_eq!(t.pose(0.25).fov_deg, None);
    }

    #[test]
    fn bad_tracks_name_the_line_and_field() {
        for (text, line, needle) in [
            (
                "time,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,1\n1,0,0,zero,0,0,0,1\n",
                3,
                "field `z`",
            ),
            (
                "time,x,y,z,qx,qy,qz,qw\n1,0,0,0,0,0,0,1\n1,0,0,0,0,0,0,1\n",
                3,
                "increase",
            ),
            ("time,x,y,z,qx,qy,qz,qw\n0,0,0,0,0,0,0,2\n", 2, "length 2"),
            ("time,x,y,z,roll\n", 1, "unknown column \"roll\""),
            ("time,x,y,z\n", 1, "orientation"),
            (
                "time,x,y,z,look_x,look_y,look_z\n0,1,1,1,1,1,1\n",
                2,
                "look-at",
            ),
            (
                "time,x,y,z,qx,qy,qz,qw,fov_deg\n0,0,0,0,0,0,0,1,180\n",
                2,
                "fov_deg",
            ),
        ] {
            let (_d, p) = write(text);
            let e = CameraTrack::read_csv(&p, 24.0).unwrap_err().to_string();
            assert!(e.contains(&format!("track.csv:{line}:")), "{e}");
            assert!(e.contains(needle), "{e}");
        }
        let (_d, p) = write("time,x,y,z,qx,qy,qz,qw\n");
        assert!(
            CameraTrack::read_csv(&p, 24.0)
                .unwrap_err()
                .to_string()
                .contains("no rows")
        );
    }
}
