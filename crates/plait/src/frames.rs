//! Rendering a sequence of frames: time = frame index / fps drives the
//! scene's `[animation]` and `FrameUniforms` (time, head pose now and one
//! frame earlier, the light fitted to the hair where it is), and every frame
//! is rendered, timed and handed to the caller. `plait render --frames`,
//! `plait ab`'s temporal metric and tests share it.

use glam::Mat4;
use plait_gpu::FrameReport;
use plait_gpu::frame::FrameUniforms;
use plait_hair::Strands;

use crate::session::{Prepared, SceneData, SessionError};

/// Where the scene is at one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FramePose {
    pub index: u32,
    /// Seconds: index / fps.
    pub time: f32,
    /// The head's world-from-rest matrix now and one frame earlier.
    pub head: Mat4,
    pub head_previous: Mat4,
    /// The camera's distance to its target as a factor of the scene's (the
    /// animation's `camera_distance`, a dolly; 1 = the scene's camera).
    pub camera_distance: f32,
}

impl FramePose {
    /// Frame `index` of an animation played at `fps` frames a second.
    pub fn at(scene: &SceneData, index: u32, fps: f32) -> Self {
        let time = index as f32 / fps;
        let previous = index.saturating_sub(1) as f32 / fps;
        FramePose {
            index,
            time,
            head: scene.scene.head_model(time),
            head_previous: scene.scene.head_model(previous),
            camera_distance: scene.scene.camera_distance(time),
        }
    }
}

impl SceneData {
    /// The hair posed for `head`: without simulation the groom follows the
    /// head rigidly (its roots sit on the head). `None` for the rest pose.
    pub fn hair_posed(&self, head: Mat4) -> Option<Strands> {
        if head == Mat4::IDENTITY {
            return None;
        }
        let mut moved = self.strands.clone();
        for p in &mut moved.points {
            *p = head.transform_point3(*p);
        }
        Some(moved)
    }

    /// Standard inputs of the frame at `pose`, with `hair` where the hair is
    /// (the light's frustum is fitted to it and to the posed head).
    pub fn frame_posed(
        &self,
        size: (u32, u32),
        pose: &FramePose,
        hair: Option<&Strands>,
    ) -> FrameUniforms {
        let hair = hair.unwrap_or(&self.strands);
        let bounds = self
            .scene
            .opaque_bounds_posed(pose.head)
            .union(&hair.bounds());
        let camera = self.scene.camera.dollied(pose.camera_distance);
        FrameUniforms::seen_from(&camera, &self.scene, hair, bounds, size, pose.index).with_motion(
            pose.time,
            pose.head,
            pose.head_previous,
        )
    }
}

/// One frame rendered and checked: what the session's frame step hands a
/// front end (`plait render`, `--frames`, `plait ab`, the probes, the viewer).
#[derive(Clone, Debug)]
pub struct Frame {
    /// Per-pass times and every overflow counter as the frame left it.
    pub report: FrameReport,
    /// One line per bounded buffer the user capped that dropped data this
    /// frame (a cap reports and the frame goes on; a drop nobody chose is an
    /// error instead, [`crate::overflow::check_frame`]).
    pub dropped: Vec<String>,
    /// Level-of-detail notes of this frame's camera: strands or wisps left
    /// out on purpose ([`crate::strand_lod::note`], [`crate::wisps::lod_note`]).
    pub notes: Vec<String>,
}

impl Prepared<'_> {
    /// The inputs of the next frames (camera, light, time, size).
    pub fn set_frame(&mut self, frame: &FrameUniforms) {
        self.renderer.set_frame(frame);
        self.uniforms = *frame;
    }

    /// Render one frame with the inputs set last, then the checks every
    /// frame owes: data dropped from a buffer nobody sized, or invocations
    /// cut short, fail it ([`SessionError::Dropped`]); a user's cap that
    /// dropped is in [`Frame::dropped`].
    pub fn render(&self) -> Result<Frame, SessionError> {
        self.checked(self.renderer.render()?)
    }

    /// [`Prepared::render`] for a caller that cannot block on the GPU (the
    /// browser, `crates/plait-web`): the same frame step and checks, the
    /// readback awaited.
    pub async fn render_async(&self) -> Result<Frame, SessionError> {
        self.checked(self.renderer.render_async().await?)
    }

    /// [`Prepared::read_resource`], awaited ([`Prepared::render_async`]).
    pub async fn read_resource_async(
        &self,
        name: &str,
    ) -> Result<plait_gpu::readback::TexelData, plait_gpu::GpuError> {
        self.renderer.read_resource_async(name).await
    }

    /// The checks every frame owes, and its notes, on a rendered frame.
    fn checked(&self, report: FrameReport) -> Result<Frame, SessionError> {
        let dropped = crate::overflow::check_frame(&report)?;
        let schedule = self.schedule();
        let mut notes: Vec<String> = crate::strand_lod::note(schedule, &self.uniforms)
            .into_iter()
            .collect();
        if let Some(count) = self.wisp_count {
            notes.extend(crate::wisps::lod_note(
                &self.uniforms,
                self.wisp_lod_fraction,
                count,
            ));
        }
        Ok(Frame {
            report,
            dropped,
            notes,
        })
    }

    /// Render frame `index` of the scene's animation at `fps`: the hair
    /// follows the head (uploaded only when its pose changed), then the
    /// frame's inputs are set and the frame rendered and checked
    /// ([`Prepared::render`]).
    pub fn render_frame(
        &mut self,
        scene: &SceneData,
        size: (u32, u32),
        index: u32,
        fps: f32,
    ) -> Result<Frame, SessionError> {
        let frame = self.pose_frame(scene, size, index, fps)?;
        self.set_frame(&frame);
        self.render()
    }

    /// Moves the hair to frame `index` (uploaded only when its pose
    /// changed) and returns the frame's inputs, for a caller that adjusts
    /// them before rendering (the visibility probe turns the jitter off).
    pub fn pose_frame(
        &mut self,
        scene: &SceneData,
        size: (u32, u32),
        index: u32,
        fps: f32,
    ) -> Result<FrameUniforms, SessionError> {
        let pose = FramePose::at(scene, index, fps);
        let hair = scene.hair_posed(pose.head);
        if self.hair_follows_head && self.hair_pose != pose.head {
            self.renderer
                .set_hair(hair.as_ref().unwrap_or(&scene.strands))?;
            self.hair_pose = pose.head;
        }
        Ok(scene
            .frame_posed(size, &pose, hair.as_ref())
            .with_strand_coverage(crate::session::strand_coverage(self.schedule())))
    }
}

/// Per-pass GPU times of a sequence, as medians over the frames in which the
/// pass ran: a `run = "once"` pass counts its first frame only (later frames
/// repeat that time as `cached`), and frames without a time (no timestamp
/// queries) do not count.
pub fn median_report(frames: &[FrameReport]) -> Option<FrameReport> {
    let first = frames.first()?;
    let median = |mut xs: Vec<f64>| -> Option<f64> {
        if xs.is_empty() {
            return None;
        }
        xs.sort_by(f64::total_cmp);
        let n = xs.len();
        Some(if n % 2 == 1 {
            xs[n / 2]
        } else {
            (xs[n / 2 - 1] + xs[n / 2]) / 2.0
        })
    };
    let passes = first
        .passes
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let mut timing = p.clone();
            timing.cached = false;
            timing.gpu_ms = median(
                frames
                    .iter()
                    .filter_map(|f| f.passes.get(i).filter(|q| !q.cached).and_then(|q| q.gpu_ms))
                    .collect(),
            );
            timing
        })
        .collect();
    // Drops: each counter's worst frame, so a sequence that dropped says so.
    let overflow = first
        .overflow
        .iter()
        .enumerate()
        .map(|(i, o)| {
            frames
                .iter()
                .filter_map(|f| f.overflow.get(i))
                .max_by_key(|o| o.dropped)
                .unwrap_or(o)
                .clone()
        })
        .collect();
    Some(FrameReport {
        passes,
        total_gpu_ms: median(frames.iter().filter_map(|f| f.total_gpu_ms).collect()),
        overflow,
    })
}

/// Renders frames `0..frames` at `fps`, handing each checked frame's index,
/// frame and image to `each` (which may stop the run with an error), and
/// returns every frame.
pub fn render_sequence<E: From<SessionError>>(
    prepared: &mut Prepared,
    scene: &SceneData,
    size: (u32, u32),
    frames: u32,
    fps: f32,
    mut each: impl FnMut(u32, &Frame, image::RgbaImage) -> Result<(), E>,
) -> Result<Vec<Frame>, E> {
    let mut rendered = Vec::with_capacity(frames as usize);
    for index in 0..frames {
        let frame = prepared.render_frame(scene, size, index, fps)?;
        let image = prepared.image().map_err(SessionError::from)?;
        each(index, &frame, image)?;
        rendered.push(frame);
    }
    Ok(rendered)
}

#[cfg(test)]
mod tests {
    use super::*;
    use plait_gpu::PassTiming;

    /// Pass times of one frame: (ms, cached).
    fn report(times: &[(Option<f64>, bool)], total: f64) -> FrameReport {
        FrameReport {
            passes: times
                .iter()
                .enumerate()
                .map(|(i, &(gpu_ms, cached))| PassTiming {
                    name: format!("p{i}"),
                    type_name: "t".into(),
                    gpu_ms,
                    stats: Vec::new(),
                    cached,
                })
                .collect(),
            total_gpu_ms: Some(total),
            overflow: Vec::new(),
        }
    }

    #[test]
    fn medians_per_pass_count_the_frames_it_ran() {
        let frames = [
            report(
                &[(Some(5.0), false), (Some(1.0), false), (None, false)],
                10.0,
            ),
            report(
                &[(Some(1.0), false), (Some(1.0), true), (None, false)],
                30.0,
            ),
            report(
                &[(Some(3.0), false), (Some(1.0), true), (None, false)],
                20.0,
            ),
            report(
                &[(Some(100.0), false), (Some(1.0), true), (None, false)],
                11.0,
            ),
        ];
        let m = median_report(&frames).expect("frames");
        assert_eq!(m.passes[0].gpu_ms, Some(4.0));
        assert_eq!(m.passes[1].gpu_ms, Some(1.0), "the pass that ran once");
        assert!(!m.passes[1].cached);
        assert_eq!(m.passes[2].gpu_ms, None, "no timestamps");
        assert_eq!(m.total_gpu_ms, Some(15.5));
        assert!(median_report(&[]).is_none());
    }
}
