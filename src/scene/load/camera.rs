//! The `camera` section: eye, centre and (3D) `up` → the observer frame, the projection, `p`,
//! the window and the resolution.

use super::dim::LoadDim;
use super::required_vector;
use super::schema::{DEFAULT_P, DEFAULT_PROJECTION, MAX_RESOLUTION};
use crate::format::as_written;
use crate::geom::frame::FrameError;
use crate::json::reader::{positive, type_name, Reader};
use crate::json::Value;
use crate::scene::camera::{Camera, Projection, Window};

/// The camera at `camera`, every field checked.
pub(super) fn read<V: LoadDim>(r: &mut Reader, v: &Value) -> Option<Camera<V>> {
    let cam = r.fields(v, "camera", V::CAMERA)?;
    let eye = required_vector::<V>(r, cam, "camera", "eye");
    let center = required_vector::<V>(r, cam, "camera", "center");
    let frame = match (eye, center) {
        (Some(e), Some(c)) => V::frame(r, cam, e, c),
        _ => None,
    };
    let projection = match cam.get("projection") {
        None => Some(DEFAULT_PROJECTION),
        Some(p) => match r.string(p, "camera.projection") {
            Some("perspective") => Some(Projection::Perspective),
            Some("orthographic") => Some(Projection::Orthographic),
            Some(other) => {
                r.err(
                    "camera.projection",
                    format!("must be \"perspective\" or \"orthographic\", got \"{other}\""),
                );
                None
            }
            None => None,
        },
    };
    let p = r.optional(cam, "camera", "p", DEFAULT_P, positive);
    let window = match cam.get("window") {
        Some(w) => read_window::<V>(r, w),
        None => {
            r.err("camera.window", "missing (required)");
            None
        }
    };
    let (nx, ny) = match cam.get("resolution") {
        Some(Value::Array(res)) if !res.is_empty() => {
            let nx = resolution_axis(r, &res[0], "camera.resolution[0]");
            let ny = V::rows(r, res, "camera.resolution");
            (nx, ny)
        }
        Some(other) => {
            r.err("camera.resolution", format!("must be an array of pixel counts, got {}", type_name(other)));
            (None, None)
        }
        None => {
            r.err("camera.resolution", "missing (required)");
            (None, None)
        }
    };
    Some(Camera {
        eye: eye?,
        center: center?,
        frame: frame?.0,
        up: frame?.1,
        projection: projection?,
        p,
        window: window?,
        nx: nx?,
        ny: ny?,
    })
}

/// Says why eye, centre and up make no frame.
pub(super) fn frame_error(r: &mut Reader, e: FrameError) {
    match e {
        FrameError::EyeIsCenter => r.err("camera.center", "must differ from camera.eye"),
        FrameError::UpParallel => r.err("camera.up", "parallel to eye − center (or zero): no camera frame"),
    }
}

/// One axis of `camera.resolution`: pixels in `[1, MAX_RESOLUTION]`.
pub(super) fn resolution_axis(r: &mut Reader, v: &Value, path: &str) -> Option<usize> {
    r.integer(v, path, 1, MAX_RESOLUTION).and_then(|n| usize::try_from(n).ok())
}

fn read_window<V: LoadDim>(r: &mut Reader, v: &Value) -> Option<Window> {
    let w = r.fields(v, "camera.window", V::WINDOW)?;
    let l = r.required(w, "camera.window", "l");
    let rr = r.required(w, "camera.window", "r");
    let (b, t) = if V::DIM == 3 {
        (r.required(w, "camera.window", "b"), r.required(w, "camera.window", "t"))
    } else {
        (Some(0.0), Some(0.0))
    };
    let (l, rr, b, t) = (l?, rr?, b?, t?);
    let mut ok = true;
    if rr <= l {
        r.err("camera.window", format!("r must be > l, got l = {}, r = {}", as_written(l), as_written(rr)));
        ok = false;
    }
    if V::DIM == 3 && t <= b {
        r.err("camera.window", format!("t must be > b, got b = {}, t = {}", as_written(b), as_written(t)));
        ok = false;
    }
    // The window's width must itself be finite and non-zero in f64.
    if !((rr - l).is_finite() && (t - b).is_finite()) {
        r.err("camera.window", "too large: its sides overflow");
        ok = false;
    }
    ok.then_some(Window { l, r: rr, b, t })
}
