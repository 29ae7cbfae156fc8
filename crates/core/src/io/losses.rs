//! What an output format cannot hold of a scene, said before it is written: a user who
//! decimates a textured, coloured VRML scene to STL should hear that the colours and the
//! texture stay behind, not find out in another program. One message per kind of loss,
//! with how many models it touches.
//!
//! What each writer keeps (see their modules): VRML 2.0 everything; OBJ per-vertex colours
//! and texture coordinates per model; PLY and OFF hold all models in one vertex list, so
//! per-vertex colours and texture coordinates only when every model has them (PLY also
//! names one texture image shared by all); STL geometry only, in 32-bit floats (far
//! coordinates rounded). Per-face colours are VRML's alone.

use std::path::Path;

use super::Format;
use crate::mesh::{Attribute, Model, Scene};

/// The warnings for writing `scene` to `output`: [`losses`] for its format, and for glTF
/// the texture images that cannot be embedded or copied (`gltf::image_losses`); for other
/// formats, what a glTF source carried through (skins, cameras, lights, lines, extras).
pub fn losses_at(scene: &Scene, output: &Path) -> Vec<String> {
    let format = Format::from_path(output);
    let mut out = losses(scene, format);
    if matches!(format, Some(Format::Gltf | Format::Glb)) {
        out.extend(super::gltf::image_losses(scene, output));
    } else {
        out.extend(gltf_only(scene));
    }
    out
}

/// What a glTF source carries that only a glTF output keeps, said once: "the source's
/// skins, cameras and extras are glTF's alone ...".
fn gltf_only(scene: &Scene) -> Option<String> {
    let copied = scene
        .models
        .iter()
        .find_map(|m| m.instance.as_ref()?.tree.copied.as_ref())?;
    let kinds = super::gltf::carried_kinds(copied);
    let (last, rest) = kinds.split_last()?;
    let named = match rest.is_empty() {
        true => last.clone(),
        false => format!("{} and {last}", rest.join(", ")),
    };
    let posed = kinds
        .iter()
        .any(|k| matches!(k.as_str(), "skins" | "morph targets" | "animations"));
    let fate = match (posed, kinds.len() > 1 || !posed) {
        (true, false) => "this one keeps the meshes at rest",
        (true, true) => "this one leaves them out and keeps the meshes at rest",
        (false, _) => "this one leaves them out",
    };
    Some(format!(
        "the source's {named} are glTF's alone: a glTF output carries them, {fate}"
    ))
}

/// The warnings for writing `scene` in `format` (`None`: VRML 2.0, the default).
pub fn losses(scene: &Scene, format: Option<Format>) -> Vec<String> {
    let format = format.unwrap_or(Format::Vrml2);
    let name = match format {
        // glTF keeps per-face colours by giving each triangle corner its own vertex.
        Format::Vrml2 | Format::Gltf | Format::Glb => return Vec::new(),
        Format::Ply => "PLY",
        Format::Obj => "OBJ",
        Format::Stl => "STL",
        Format::Off => "OFF",
    };
    let counts = Counts::of(&scene.models);
    let keeps = Keeps::of(scene, format, &counts);
    let mut out = attribute_losses(name, format, &counts, &keeps);
    if keeps.images {
        out.extend(wrap_loss(name, format, &scene.models));
    }
    if format == Format::Stl {
        out.extend(far_loss(&scene.models));
    }
    out
}

/// Binary STL holds 32-bit coordinates: models far from zero lose digits there.
fn far_loss(models: &[Model]) -> Option<String> {
    let far: Vec<&Model> = models
        .iter()
        .filter(|m| m.origin != glam::DVec3::ZERO)
        .collect();
    let largest = far
        .iter()
        .map(|m| m.origin.abs().max_element())
        .fold(0.0, f64::max);
    if far.is_empty() {
        return None;
    }
    // f32's step at that magnitude: 2^-23 of the power of two at or below it.
    let step = (largest.log2().floor() - 23.0).exp2();
    Some(format!(
        "binary STL holds 32-bit coordinates: {} far from zero (up to {largest}) {} rounded \
         to steps of {step} there; PLY, OBJ or OFF keep every digit",
        if far.len() == 1 {
            "1 model".to_string()
        } else {
            format!("{} models", far.len())
        },
        if far.len() == 1 { "is" } else { "are" },
    ))
}

/// How many models have each attribute.
struct Counts {
    vertex_colored: usize,
    face_colored: usize,
    textured: usize,
    imaged: usize,
    all: usize,
}

impl Counts {
    fn of(models: &[Model]) -> Self {
        let count = |has: fn(&Model) -> bool| models.iter().filter(|m| has(m)).count();
        Self {
            vertex_colored: count(|m| matches!(m.colors, Some(Attribute::PerVertex(_)))),
            face_colored: count(|m| matches!(m.colors, Some(Attribute::PerFace(_)))),
            textured: count(|m| m.texcoords.is_some()),
            imaged: count(|m| m.texcoords.is_some() && m.texture.is_some()),
            all: models.len(),
        }
    }
}

/// Whether the format keeps each attribute, given how many models have it.
struct Keeps {
    vertex_colors: bool,
    face_colors: bool,
    texcoords: bool,
    images: bool,
}

impl Keeps {
    fn of(scene: &Scene, format: Format, c: &Counts) -> Self {
        let vertex_colors = match format {
            Format::Obj => true,
            Format::Ply | Format::Off => c.vertex_colored == c.all,
            _ => false,
        };
        // PLY and OFF write colours on their face records when every model has them per face.
        let face_colors = matches!(format, Format::Ply | Format::Off) && c.face_colored == c.all;
        let texcoords = match format {
            Format::Obj => true,
            Format::Ply | Format::Off => c.textured == c.all,
            _ => false,
        };
        let images = texcoords
            && match format {
                Format::Obj => true,
                Format::Ply => super::ply::shared_texture(scene).is_some(),
                _ => false,
            };
        Self {
            vertex_colors,
            face_colors,
            texcoords,
            images,
        }
    }
}

/// The colours, texture coordinates and image names the `name` output loses.
fn attribute_losses(name: &str, format: Format, c: &Counts, keeps: &Keeps) -> Vec<String> {
    let all = c.all;
    let one_list = matches!(format, Format::Ply | Format::Off);
    let have = |n: usize| {
        if n == 1 {
            "1 model has them".to_string()
        } else {
            format!("{n} models have them")
        }
    };
    let why = |n: usize| {
        if one_list && n < all {
            format!(
                " ({n} of {all} models; {name} holds all models in one vertex list: all or none)"
            )
        } else {
            format!(" ({})", have(n))
        }
    };
    let mut out = Vec::new();
    if c.vertex_colored > 0 && !keeps.vertex_colors {
        out.push(format!(
            "{name} output keeps no per-vertex colours{}",
            why(c.vertex_colored)
        ));
    }
    if c.face_colored > 0 && !keeps.face_colors {
        let which = match format {
            Format::Ply | Format::Off => why(c.face_colored),
            _ => format!(
                " ({}; VRML 2.0, PLY and OFF keep them)",
                have(c.face_colored)
            ),
        };
        out.push(format!("{name} output keeps no per-face colours{which}"));
    }
    if c.textured > 0 && !keeps.texcoords {
        out.push(format!(
            "{name} output keeps no texture coordinates{}",
            why(c.textured)
        ));
    } else if c.imaged > 0 && !keeps.images {
        let reason = if format == Format::Ply {
            "; a PLY names one image for all models"
        } else {
            ""
        };
        out.push(format!(
            "{name} output does not name the texture image ({}{reason})",
            have(c.imaged)
        ));
    }
    out
}

/// A texture that does not repeat: OBJ's `-clamp` covers both directions at once, PLY
/// says nothing of wrapping.
fn wrap_loss(name: &str, format: Format, models: &[Model]) -> Option<String> {
    let wrap_lost = models
        .iter()
        .filter(|m| m.texcoords.is_some() && m.texture.is_some())
        .filter(|m| match format {
            Format::Obj => m.texture_repeat[0] != m.texture_repeat[1],
            _ => m.texture_repeat != [true; 2],
        })
        .count();
    if wrap_lost == 0 {
        return None;
    }
    let reason = if format == Format::Obj {
        "an MTL clamps a texture along both directions or neither"
    } else {
        "a PLY does not say how a texture wraps"
    };
    Some(format!(
        "{name} output writes the texture as repeating where the input clamps it \
         ({wrap_lost} of {} models; {reason})",
        models.len()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    fn textured(image: Option<&str>) -> Model {
        let mut m = shapes::cube(2, 1.0);
        m.texcoords = Some(vec![[0.5, 0.5]; m.positions.len()]);
        m.texture = image.map(str::to_string);
        m
    }

    fn colored() -> Model {
        let mut m = shapes::cube(2, 1.0);
        m.colors = Some(Attribute::PerVertex(vec![
            [1.0, 0.0, 0.0];
            m.positions.len()
        ]));
        m
    }

    #[test]
    fn vrml_and_plain_geometry_lose_nothing() {
        let scene = Scene {
            models: vec![textured(Some("a.png")), colored()],
        };
        assert!(losses(&scene, None).is_empty());
        assert!(losses(&scene, Some(Format::Vrml2)).is_empty());
        let plain = Scene {
            models: vec![shapes::cube(2, 1.0)],
        };
        for f in [Format::Ply, Format::Obj, Format::Stl, Format::Off] {
            assert!(losses(&plain, Some(f)).is_empty(), "{f:?}");
        }
    }

    #[test]
    fn stl_names_everything_it_drops() {
        let mut faced = shapes::cube(2, 1.0);
        faced.colors = Some(Attribute::PerFace(vec![[0.0; 3]; faced.triangles.len()]));
        let scene = Scene {
            models: vec![textured(Some("a.png")), colored(), faced],
        };
        assert_eq!(
            losses(&scene, Some(Format::Stl)),
            vec![
                "STL output keeps no per-vertex colours (1 model has them)",
                "STL output keeps no per-face colours (1 model has them; VRML 2.0, PLY and OFF keep them)",
                "STL output keeps no texture coordinates (1 model has them)",
            ]
        );
    }

    #[test]
    fn ply_and_off_keep_attributes_only_when_every_model_has_them() {
        let mixed = Scene {
            models: vec![textured(None), shapes::cube(2, 1.0)],
        };
        assert_eq!(
            losses(&mixed, Some(Format::Off)),
            vec![
                "OFF output keeps no texture coordinates (1 of 2 models; OFF holds all models \
                 in one vertex list: all or none)"
            ]
        );
        assert!(losses(&mixed, Some(Format::Obj)).is_empty());
        let two_images = Scene {
            models: vec![textured(Some("a.png")), textured(Some("b.png"))],
        };
        assert_eq!(
            losses(&two_images, Some(Format::Ply)),
            vec![
                "PLY output does not name the texture image (2 models have them; a PLY names \
                 one image for all models)"
            ]
        );
        let one_image = Scene {
            models: vec![textured(Some("a.png")), textured(Some("a.png"))],
        };
        assert!(losses(&one_image, Some(Format::Ply)).is_empty());
        // Clamped along u only: neither OBJ nor PLY can say so; clamped both ways, OBJ can.
        let mut half = one_image.clone();
        half.models[0].texture_repeat = [false, true];
        for (f, reason) in [
            (
                Format::Obj,
                "an MTL clamps a texture along both directions or neither",
            ),
            (Format::Ply, "a PLY does not say how a texture wraps"),
        ] {
            assert_eq!(
                losses(&half, Some(f)),
                vec![format!(
                    "{} output writes the texture as repeating where the input clamps it \
                     (1 of 2 models; {reason})",
                    if f == Format::Obj { "OBJ" } else { "PLY" }
                )]
            );
        }
        half.models[0].texture_repeat = [false; 2];
        assert!(losses(&half, Some(Format::Obj)).is_empty());
        assert_eq!(
            losses(&one_image, Some(Format::Off)),
            vec!["OFF output does not name the texture image (2 models have them)"]
        );
    }
}
