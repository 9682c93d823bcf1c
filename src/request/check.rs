//! `whitted check`'s answer for a valid scene: what it models — dimension, objects by type,
//! lights, which ray kinds can occur and why, the depth, and whether `render` takes its
//! resolution (`render::check_fits`). (Its errors are `scene::load`'s, one line
//! per problem with its JSON path.)

use crate::lang::Lang;
use crate::render::{check_fits, RenderConfig};
use crate::scene::camera::Projection;
use crate::scene::{AnyScene, Scene};
use crate::shape::Dim;
use std::collections::BTreeMap;
use std::fmt::Write;

/// What `whitted check` prints for a valid scene called `name`: `NAME: valid` and the lines of
/// [`describe`].
#[must_use]
pub fn report(scene: &AnyScene, name: &str) -> String {
    let text = match scene {
        AnyScene::Flat(s) => describe(s),
        AnyScene::Space(s) => describe(s),
    };
    format!("{name}: valid\n{text}")
}

/// What a valid scene models, a few lines for a person.
#[must_use]
pub fn describe<V: Dim>(scene: &Scene<V>) -> String {
    let mut out = String::new();
    let cam = &scene.camera;
    let projection = match cam.projection {
        Projection::Perspective => "perspective",
        Projection::Orthographic => "orthographic",
    };
    let image =
        if V::DIM == 2 { format!("{} pixels", cam.nx) } else { format!("{}x{} pixels", cam.nx, cam.ny) };
    let _ = writeln!(out, "  dimension: {} ({projection} camera, {image}, p = {})", V::NAME, cam.p);
    // A resolution the scene format accepts may still be more than `render` draws.
    if let Err(why) = check_fits(scene, &RenderConfig::centers(scene.max_depth), 1) {
        let _ = writeln!(out, "  render: refused at this resolution: {why}");
    }
    let mut by_type: BTreeMap<&str, usize> = BTreeMap::new();
    for o in &scene.objects {
        *by_type.entry(o.shape.kind()).or_default() += 1;
    }
    let types: Vec<String> = by_type.iter().map(|(k, n)| format!("{n} {k}")).collect();
    let _ = writeln!(
        out,
        "  objects: {}{}",
        scene.objects.len(),
        if types.is_empty() {
            " (the image is the background)".to_string()
        } else {
            format!(" ({})", types.join(", "))
        }
    );
    for (i, o) in scene.objects.iter().enumerate() {
        if let crate::shape::Shape::Mesh(m) = &o.shape {
            use crate::shape::Parts;
            let _ = writeln!(
                out,
                "  mesh {}: {} triangles, {} degenerate skipped",
                scene.object_label(i, Lang::En),
                m.count(),
                m.skipped()
            );
        }
    }
    let _ = writeln!(out, "  lights: {}", scene.lights.len());
    let _ = writeln!(out, "  materials: {}", scene.materials.len());
    let _ = writeln!(out, "  max_depth: {} ({})", scene.max_depth, depth_meaning(scene.max_depth));
    let _ = writeln!(out, "  rays that can occur:");
    let _ = writeln!(out, "    primary: yes, one per pixel centre");
    let shadow = if scene.lights.is_empty() || scene.objects.is_empty() {
        "no: no lights or no objects".to_string()
    } else {
        format!("yes, at most one per light ({}) at every hit where N·L > 0", scene.lights.len())
    };
    let _ = writeln!(out, "    shadow: {shadow}");
    let names = |pred: &dyn Fn(usize) -> bool| -> Vec<String> {
        (0..scene.objects.len()).filter(|i| pred(*i)).map(|i| scene.object_label(i, Lang::En)).collect()
    };
    let secondary = |kind: &str, field: &str, objs: Vec<String>| {
        if scene.max_depth == 0 {
            format!("    {kind}: no: max_depth = 0 is ray casting")
        } else if objs.is_empty() {
            format!("    {kind}: no: no object has {field} > 0")
        } else {
            format!("    {kind}: yes, from {} ({field} > 0)", objs.join(", "))
        }
    };
    let _ = writeln!(out, "{}", secondary("reflected", "ks", names(&|i| scene.material_of(i).reflects())));
    let _ = writeln!(out, "{}", secondary("transmitted", "kt", names(&|i| scene.material_of(i).transmits())));
    out
}

fn depth_meaning(d: u32) -> String {
    match d {
        0 => "ray casting: no secondary rays".into(),
        1 => "one generation of secondary rays".into(),
        n => format!("up to {n} generations of secondary rays"),
    }
}
