//! `camera-frame` (lecture "Calculul razelor primare (1)", algorithm.md §2 "Camera frame"): the
//! observer frame that lookAt(O, C, up) built for the scene — `w = (O − C)/|O − C|`,
//! `u = (up × w)/|up × w|`, `v = w × u` (in 2D `u = (w_y, −w_x)`) — read from the loaded camera,
//! with the view window on the image plane at distance p along −w, its corners (l, t) and (r, b),
//! and one recorded primary ray P through its pixel's window point S. A 3D camera is drawn in an
//! oblique view (a fixed direction in its own frame, so that u, v and w fan out); 2D keeps the
//! scene's axes. The scene's objects are left out: the figure is about the frame.

use glam::DVec2;

use super::Input;
use crate::canvas::{Drawing, LegendIcon, Pen};
use crate::figure::labels::Label;
use crate::figure::parts::{draw_observer, draw_ray, label, label_outward, legend_points, legend_role};
use crate::figure::plane::{PagePlane, Planar};
use crate::figure::source::Target;
use crate::figure::style::{self, RayRole};
use crate::figure::FigureError;
use crate::format::slide_number;

/// How much of u leans into page x and out of page y in the oblique view: the page is spanned
/// by `−w + OBLIQUE·u` and `v − OBLIQUE·u`, so that w, v and u point left, up and down-right.
const OBLIQUE: f64 = 0.5;

/// The drawn length of u, v and w, as a share of the larger of p and the window's half-sides.
const AXIS_SHARE: f64 = 0.7;

/// The stroke of the frame's axes u, v, w.
fn axis_pen() -> Pen {
    Pen::solid(style::BLACK, style::CONSTRUCTION_WIDTH)
}

/// The stroke of the `up` vector: it is an input, not an axis.
fn up_pen() -> Pen {
    Pen::solid(style::REDDISH_PURPLE, style::CONSTRUCTION_WIDTH).dashed(style::CONSTRUCTION_DASH)
}

/// A vector as a slide writes it: `(0.5, 0, −1)`.
fn vector_text<V: Planar>(v: V) -> String {
    let parts: Vec<String> = (0..V::DIM).map(|a| slide_number(v[a])).collect();
    format!("({})", parts.join(", "))
}

/// Draws the figure.
///
/// # Errors
/// When no trace was recorded.
pub fn draw<V: Planar>(input: &Input<'_, V>, d: &mut Drawing) -> Result<(), FigureError> {
    let traced = input.main()?;
    let (scene, lang) = (input.scene, input.lang);
    let cam = &scene.camera;
    let f = cam.frame;
    let three = V::DIM == 3;
    let world = PagePlane::spanned(V::ZERO, V::axis(0), V::axis(1));
    let plane =
        if three { PagePlane::spanned(cam.eye, -f.w + f.u * OBLIQUE, f.v - f.u * OBLIQUE) } else { world }
            .ok_or_else(|| FigureError("the camera frame spans no plane".into()))?;
    let win = &cam.window;
    let corners: Vec<V> = if three {
        vec![
            cam.window_point(win.l, win.b),
            cam.window_point(win.r, win.b),
            cam.window_point(win.r, win.t),
            cam.window_point(win.l, win.t),
        ]
    } else {
        vec![cam.window_point(win.l, 0.0), cam.window_point(win.r, 0.0)]
    };
    let size = cam.p.max((win.r - win.l) / 2.0).max(if three { (win.t - win.b) / 2.0 } else { 0.0 });
    let length = AXIS_SHARE * size;
    let o = plane.point(cam.eye);
    let c = plane.point(cam.center);
    let axis_tip = |v: V| plane.point(cam.eye + v * length);
    let up = if three { cam.up.try_unit() } else { None };
    let on_axis = plane.point(cam.eye - f.w * cam.p);
    // The recorded primary ray through the traced pixel's S, as far as its hit or C's depth.
    let root = traced.log.nodes.first().ok_or_else(|| FigureError("no primary ray was recorded".into()))?;
    let s_point = traced.targets.first().and_then(|t| match t {
        Target::Pixel { uv, .. } => Some(cam.window_point(uv[0], uv.get(1).copied().unwrap_or(0.0))),
        Target::Ray => None,
    });
    let reach = (cam.center - cam.eye).length() * 1.1;
    let ray_end = root.end.as_ref().and_then(|e| e.hit).map_or_else(
        || root.start.origin + root.start.direction * reach,
        |h| if h.t <= reach { h.point } else { root.start.origin + root.start.direction * reach },
    );

    d.set_title(input.t(Label::TitleCameraFrame));
    let mut caption =
        format!("{} · O = {}, C = {}", input.traced(traced), vector_text(cam.eye), vector_text(cam.center));
    if three {
        caption.push_str(&format!(
            ", up = {} → w = (O − C)/|O − C| = {}, u = (up × w)/|up × w| = {}, v = w × u = {}",
            vector_text(cam.up),
            vector_text(f.w),
            vector_text(f.u),
            vector_text(f.v)
        ));
    } else {
        caption.push_str(&format!(
            " → w = (O − C)/|O − C| = {}, u = (w_y, −w_x) = {}",
            vector_text(f.w),
            vector_text(f.u)
        ));
    }
    caption.push_str(&format!(" · p = {}", slide_number(cam.p)));
    if let Some(s) = s_point {
        let sum = if three { "O + u·u + v·v − p·w" } else { "O + u·u − p·w" };
        caption.push_str(&format!(" · S = {sum} = {}", vector_text(s)));
    }
    if three {
        caption.push_str(&format!(" · {}", input.t(Label::ObliqueView)));
    }
    d.set_caption(&caption);
    d.legend_entry(input.t(Label::FrameAxes), axis_pen(), LegendIcon::Arrow);
    if up.is_some() {
        d.legend_entry(input.t(Label::UpGiven), up_pen(), LegendIcon::Arrow);
    }
    d.legend_entry(input.t(Label::ViewLine), style::normal(), LegendIcon::Line);
    d.legend_entry(input.t(Label::ViewWindow), style::view_window(), LegendIcon::Line);
    legend_role(d, RayRole::Primary, lang);
    legend_points(d, lang, false, false, true);

    let mut points: Vec<DVec2> = corners.iter().map(|p| plane.point(*p)).collect();
    points.extend([o, c, axis_tip(f.u), axis_tip(f.w), plane.point(ray_end)]);
    if three {
        points.push(axis_tip(f.v));
    }
    if let Some(u) = up {
        points.push(axis_tip(u * 1.2));
    }
    d.fit_view(&points, 0.08);

    // The window on the image plane, and the line of sight from O to C through its axis point.
    let window: Vec<DVec2> = corners.iter().map(|p| plane.point(*p)).collect();
    if three {
        d.polygon("window", window.clone(), style::view_window(), Some(style::OBJECT_FILL));
    } else {
        d.segment("window", window[0], window[1], style::view_window());
    }
    d.segment("view-line", o, c, style::normal());
    d.dot("axis-point", on_axis, style::DARK_GREY);
    d.dot("center", c, style::DARK_GREY);
    d.with_events(traced.log.ray_events(0), |d| {
        draw_ray(d, RayRole::Primary, plane.point(root.start.origin), plane.point(ray_end))
    });
    if let Some(s) = s_point {
        d.marker(
            "window-point",
            plane.point(s),
            style::DOT_RADIUS * 0.8,
            style::WHITE,
            style::outline(style::DARK_GREY),
        );
    }
    let mut axes = vec![(f.w, "w"), (f.u, "u")];
    if three {
        axes.push((f.v, "v"));
    }
    for (axis, _) in &axes {
        d.arrow("axis", o, axis_tip(*axis), axis_pen());
    }
    if let Some(u) = up {
        d.arrow("up", o, axis_tip(u * 1.2), up_pen());
    }
    draw_observer(d, o);

    // Labels: the axes at their tips, O, C, p, S, P and the window's corners.
    for (axis, name) in &axes {
        let tip = axis_tip(*axis);
        label_outward(d, tip, tip - o, name);
    }
    if let Some(u) = up {
        let tip = axis_tip(u * 1.2);
        label_outward(d, tip, tip - o, "up");
    }
    label(d, o, "O");
    label(d, c, "C");
    label(d, (o + on_axis) / 2.0, &format!("p = {}", slide_number(cam.p)));
    if let Some(s) = s_point {
        label(d, plane.point(s), "S");
    }
    let (from, to) = (plane.point(root.start.origin), plane.point(ray_end));
    d.with_events(traced.log.ray_events(0), |d| label(d, from + (to - from) * 0.8, "P"));
    if three {
        label(d, window[3], "(l, t)");
        label(d, window[1], "(r, b)");
    } else {
        label(d, window[0], "l");
        label(d, window[1], "r");
    }
    Ok(())
}
