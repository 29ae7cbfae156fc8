//! Progressive meshes (H. Hoppe, "Progressive Meshes", SIGGRAPH 1996): the edge collapses of
//! a quadric decimation (`qem`), recorded in reverse as vertex splits, so that every level of
//! detail between the base mesh and the original can be rebuilt exactly.
//!
//! Numbering makes every level a prefix: the base mesh's vertices and faces come first, split
//! `i` adds vertex `base + i` and appends its faces. A level is therefore a length of the
//! vertex and face arrays plus the splits' in-place edits (the faces whose corner moves to the
//! new vertex, the position of the vertex that splits, and its colour, normal and texture
//! coordinates when the model has them), and [`Lod`] moves between levels one split or
//! collapse at a time. [`ProgressiveModel::vertex_ids`] and `face_ids` map the
//! fully refined mesh back to the original model's numbering.
//!
//! [`Recorder`] is what the collapse loop fills; [`Recorder::finish`] turns its collapses, in
//! the loop's internal numbering, into a [`ProgressiveModel`].

use std::borrow::Borrow;

use glam::Vec3;

use crate::mesh::topology::Connectivity;
use crate::mesh::{Attribute, Model};

/// One vertex split: the inverse of one edge collapse.
#[derive(Debug, Clone, PartialEq)]
pub struct VertexSplit {
    /// The vertex that splits in two; always below the new vertex's id.
    pub keep: u32,
    /// `keep`'s position before the split (coarse) and after it (fine).
    pub keep_coarse: Vec3,
    /// `keep`'s position after the split.
    pub keep_fine: Vec3,
    /// The new vertex's position; its id is the base vertex count plus this split's index.
    pub position: Vec3,
    /// Per-vertex colours, when the model has them: `keep` coarse, `keep` fine, the new one.
    pub colors: Option<[[f32; 3]; 3]>,
    /// Per-vertex normals, when the model has them, in the same order.
    pub normals: Option<[Vec3; 3]>,
    /// Texture coordinates, when the model has them, in the same order.
    pub texcoords: Option<[[f32; 2]; 3]>,
    /// Faces (ids at this level) whose `keep` corner becomes the new vertex.
    pub renamed: Vec<u32>,
    /// Faces the split appends (one on a boundary edge, two inside).
    pub added: Vec<[u32; 3]>,
    /// Per-face colours of `added`, when the model has per-face colours.
    pub added_colors: Vec<[f32; 3]>,
}

/// One model's progressive mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgressiveModel {
    /// The coarsest level, with the original's name, transform and material. Its attributes,
    /// when present, are per vertex (colours, normals, texture coordinates) or per face
    /// (colours).
    pub base: Model,
    /// Splits from the base towards the original, in order.
    pub splits: Vec<VertexSplit>,
    /// Vertex id (base and split vertices) → the original model's vertex id.
    pub vertex_ids: Vec<u32>,
    /// Face id (base and split faces) → the original model's face id.
    pub face_ids: Vec<u32>,
}

/// Every model of a scene, in scene order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ProgressiveScene {
    /// One record per model of the scene, in scene order.
    pub models: Vec<ProgressiveModel>,
}

impl ProgressiveModel {
    /// True when splits `j` and `j + 1` undo one texture-seam collapse: `qem` collapses a
    /// seam's two sides together, to one point, recorded as two collapses of twin vertices
    /// (the same positions before and after).
    fn seam_pair(&self, j: usize) -> bool {
        match (self.splits.get(j), self.splits.get(j + 1)) {
            (Some(a), Some(b)) => {
                a.keep != b.keep
                    && a.keep_coarse == b.keep_coarse
                    && a.keep_fine == b.keep_fine
                    && a.position == b.position
            }
            _ => false,
        }
    }

    /// `level`, or one level coarser when `level` would apply only the first of a seam's
    /// two splits, which would open a crack along the seam.
    pub fn whole_level(&self, level: usize) -> usize {
        if level > 0 && self.seam_pair(level - 1) {
            level - 1
        } else {
            level
        }
    }

    /// Vertices of the fully refined mesh.
    pub fn full_vertex_count(&self) -> usize {
        self.base.positions.len() + self.splits.len()
    }

    /// Faces of the fully refined mesh.
    pub fn full_face_count(&self) -> usize {
        self.base.triangles.len() + self.splits.iter().map(|s| s.added.len()).sum::<usize>()
    }

    /// The fully refined mesh in the original model's numbering: the original's connectivity,
    /// positions and attributes, exactly (vertices no face used are not part of it).
    pub fn original(&self) -> Model {
        let mut lod = Lod::new(self);
        lod.set_level(self.splits.len());
        let fine = lod.model();
        let n = self
            .vertex_ids
            .iter()
            .map(|&v| v as usize + 1)
            .max()
            .unwrap_or(0);
        let mut model = Model {
            name: fine.name.clone(),
            transform: fine.transform,
            origin: fine.origin,
            positions: vec![Vec3::ZERO; n],
            triangles: vec![[0; 3]; fine.triangles.len()],
            colors: None,
            normals: None,
            texcoords: None,
            texture: fine.texture.clone(),
            texture_repeat: fine.texture_repeat,
            material: fine.material.clone(),
            diffuse: fine.diffuse,
            crease_angle: fine.crease_angle,
            solid: fine.solid,
            instance: fine.instance.clone(),
        };
        for (pm, &orig) in self.vertex_ids.iter().enumerate() {
            model.positions[orig as usize] = fine.positions[pm];
        }
        for (pm, &orig) in self.face_ids.iter().enumerate() {
            if let Some(slot) = model.triangles.get_mut(orig as usize) {
                *slot = fine.triangles[pm].map(|v| self.vertex_ids[v as usize]);
            }
        }
        let vertex_ids = &self.vertex_ids;
        let face_ids = &self.face_ids;
        model.colors = fine.colors.as_ref().map(|a| match a {
            Attribute::PerVertex(c) => Attribute::PerVertex(scatter(c, vertex_ids, n)),
            Attribute::PerFace(c) => Attribute::PerFace(scatter(c, face_ids, fine.triangles.len())),
        });
        model.normals = fine.normals.as_ref().map(|a| match a {
            Attribute::PerVertex(v) => Attribute::PerVertex(scatter(v, vertex_ids, n)),
            Attribute::PerFace(v) => Attribute::PerFace(scatter(v, face_ids, fine.triangles.len())),
        });
        model.texcoords = fine.texcoords.as_ref().map(|t| scatter(t, vertex_ids, n));
        model
    }

    /// Checks that every index is in range for the level it is used at, so that [`Lod`]
    /// never indexes out of bounds: a file read from disk is checked before use.
    pub fn validate(&self) -> Result<(), String> {
        self.validate_base()?;
        let faces = self.validate_splits()?;
        self.validate_ids(faces)
    }

    /// The base mesh: its faces' indices and its attributes' lengths.
    fn validate_base(&self) -> Result<(), String> {
        let base_v = self.base.positions.len();
        for (t, tri) in self.base.triangles.iter().enumerate() {
            if tri.iter().any(|&v| v as usize >= base_v) {
                return Err(format!("base face {t} uses a vertex out of range"));
            }
        }
        let colors_ok = match &self.base.colors {
            None => true,
            Some(Attribute::PerVertex(c)) => c.len() == base_v,
            Some(Attribute::PerFace(c)) => c.len() == self.base.triangles.len(),
        };
        if !colors_ok {
            return Err("base colours do not match the base mesh".into());
        }
        match &self.base.normals {
            None => {}
            Some(Attribute::PerVertex(n)) if n.len() == base_v => {}
            Some(_) => return Err("base normals must be one per base vertex".into()),
        }
        if (self.base.texcoords.as_ref()).is_some_and(|t| t.len() != base_v) {
            return Err("base texture coordinates must be one pair per base vertex".into());
        }
        Ok(())
    }

    /// Each split against the level it applies to; returns the face count of the full mesh.
    fn validate_splits(&self) -> Result<usize, String> {
        let base_v = self.base.positions.len();
        let mut faces = self.base.triangles.len();
        let vertex_colors = matches!(self.base.colors, Some(Attribute::PerVertex(_)));
        let face_colors = matches!(self.base.colors, Some(Attribute::PerFace(_)));
        let normals = self.base.normals.is_some();
        let texcoords = self.base.texcoords.is_some();
        for (i, s) in self.splits.iter().enumerate() {
            let new = (base_v + i) as u32;
            if s.keep >= new {
                return Err(format!(
                    "split {i} splits vertex {} that does not exist yet",
                    s.keep
                ));
            }
            if s.renamed.iter().any(|&f| f as usize >= faces) {
                return Err(format!("split {i} renames a face that does not exist yet"));
            }
            if s.added.iter().flatten().any(|&v| v > new) {
                return Err(format!("split {i} adds a face over a vertex out of range"));
            }
            if s.colors.is_some() != vertex_colors
                || s.normals.is_some() != normals
                || s.texcoords.is_some() != texcoords
            {
                return Err(format!("split {i}: attributes differ from the base mesh's"));
            }
            if face_colors && s.added_colors.len() != s.added.len() {
                return Err(format!("split {i}: one colour per added face expected"));
            }
            faces += s.added.len();
        }
        Ok(faces)
    }

    /// The original vertex and face ids: one per vertex and face of the full mesh.
    fn validate_ids(&self, faces: usize) -> Result<(), String> {
        if self.vertex_ids.len() != self.full_vertex_count() {
            return Err("one original vertex id per vertex expected".into());
        }
        // The original's vertices no face used are not recorded, so ids may have gaps, but
        // not so many that `original` would allocate far more than the file describes.
        let bound = 2 * self.vertex_ids.len() + 1024;
        if let Some(id) = self.vertex_ids.iter().find(|&&id| id as usize >= bound) {
            return Err(format!(
                "original vertex id {id} is out of range for {} vertices",
                self.vertex_ids.len()
            ));
        }
        if (self.face_ids.iter()).any(|&id| id as usize >= 2 * faces + 1024) {
            return Err(format!(
                "an original face id is out of range for {faces} faces"
            ));
        }
        if self.face_ids.len() != faces {
            return Err("one original face id per face expected".into());
        }
        Ok(())
    }
}

fn scatter<T: Copy + Default>(values: &[T], ids: &[u32], n: usize) -> Vec<T> {
    let mut out = vec![T::default(); n];
    for (i, &id) in ids.iter().enumerate() {
        if let (Some(slot), Some(&v)) = (out.get_mut(id as usize), values.get(i)) {
            *slot = v;
        }
    }
    out
}

/// A cursor over one progressive model's levels: level 0 is the base mesh, level
/// `splits.len()` the original. Moving one level costs the one split or collapse. `P` is
/// `&ProgressiveModel` or an owning handle such as `Arc<ProgressiveModel>` (the viewer's).
#[derive(Debug, Clone)]
pub struct Lod<P: Borrow<ProgressiveModel>> {
    pm: P,
    level: usize,
    model: Model,
}

impl<P: Borrow<ProgressiveModel>> Lod<P> {
    /// At level 0, the base mesh. `pm` must have passed [`ProgressiveModel::validate`] (as
    /// every progressive model made by `qem` or read by `io::progressive` has).
    pub fn new(pm: P) -> Self {
        let model = pm.borrow().base.clone();
        Self {
            pm,
            level: 0,
            model,
        }
    }

    /// The progressive model this cursor walks.
    pub fn progressive(&self) -> &ProgressiveModel {
        self.pm.borrow()
    }

    /// The number of splits applied so far (0: the coarse mesh).
    pub fn level(&self) -> usize {
        self.level
    }

    /// The number of levels above the base.
    pub fn max_level(&self) -> usize {
        self.progressive().splits.len()
    }

    /// The mesh at the current level, in progressive numbering.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Moves to `level` (clamped to the levels there are).
    pub fn set_level(&mut self, level: usize) {
        let level = level.min(self.max_level());
        while self.level < level {
            self.refine();
        }
        while self.level > level {
            self.coarsen();
        }
    }

    /// Applies the next vertex split.
    fn refine(&mut self) {
        let s = &self.pm.borrow().splits[self.level];
        let m = &mut self.model;
        let new = m.positions.len() as u32;
        m.positions[s.keep as usize] = s.keep_fine;
        m.positions.push(s.position);
        for &f in &s.renamed {
            for corner in &mut m.triangles[f as usize] {
                if *corner == s.keep {
                    *corner = new;
                }
            }
        }
        m.triangles.extend_from_slice(&s.added);
        match &mut m.colors {
            Some(Attribute::PerVertex(c)) => {
                if let Some([_, fine, own]) = s.colors {
                    c[s.keep as usize] = fine;
                    c.push(own);
                }
            }
            Some(Attribute::PerFace(c)) => c.extend_from_slice(&s.added_colors),
            None => {}
        }
        if let (Some(Attribute::PerVertex(n)), Some([_, fine, own])) = (&mut m.normals, s.normals) {
            n[s.keep as usize] = fine;
            n.push(own);
        }
        if let (Some(t), Some([_, fine, own])) = (&mut m.texcoords, s.texcoords) {
            t[s.keep as usize] = fine;
            t.push(own);
        }
        self.level += 1;
    }

    /// Undoes the last vertex split: the edge collapse it stands for.
    fn coarsen(&mut self) {
        self.level -= 1;
        let s = &self.pm.borrow().splits[self.level];
        let m = &mut self.model;
        let new = (m.positions.len() - 1) as u32;
        m.positions.pop();
        m.positions[s.keep as usize] = s.keep_coarse;
        m.triangles.truncate(m.triangles.len() - s.added.len());
        for &f in &s.renamed {
            for corner in &mut m.triangles[f as usize] {
                if *corner == new {
                    *corner = s.keep;
                }
            }
        }
        match &mut m.colors {
            Some(Attribute::PerVertex(c)) => {
                c.pop();
                if let Some([coarse, _, _]) = s.colors {
                    c[s.keep as usize] = coarse;
                }
            }
            Some(Attribute::PerFace(c)) => c.truncate(c.len() - s.added.len()),
            None => {}
        }
        if let Some(Attribute::PerVertex(n)) = &mut m.normals {
            n.pop();
            if let Some([coarse, _, _]) = s.normals {
                n[s.keep as usize] = coarse;
            }
        }
        if let Some(t) = &mut m.texcoords {
            t.pop();
            if let Some([coarse, _, _]) = s.texcoords {
                t[s.keep as usize] = coarse;
            }
        }
    }

    /// Where each vertex of the current level was at `coarse` (a lower level): its own
    /// position there, or that of the vertex it split from — the start of a geomorph from
    /// `coarse` to this level (vertices glide from there to [`Self::model`]'s positions).
    pub fn positions_at(&self, coarse: usize) -> Vec<Vec3> {
        let coarse = coarse.min(self.level);
        let pm = self.progressive();
        let base = pm.base.positions.len();
        let splits = &pm.splits[coarse..self.level];
        // Positions at `coarse` of the vertices that exist there.
        let mut at = self.model.positions[..base + coarse].to_vec();
        for s in splits.iter().rev() {
            if (s.keep as usize) < base + coarse {
                at[s.keep as usize] = s.keep_coarse;
            }
        }
        // Each later vertex starts where its ancestor at `coarse` is.
        let mut ancestor: Vec<u32> = (0..(base + coarse) as u32).collect();
        for s in splits {
            let a = ancestor[s.keep as usize];
            ancestor.push(a);
        }
        ancestor.iter().map(|&a| at[a as usize]).collect()
    }
}

/// One edge collapse as the collapse loop performed it, in its internal numbering; its
/// renamed and deleted slots are ranges of the recorder's flat arrays.
#[derive(Debug, Clone, Copy)]
struct Collapse {
    keep: u32,
    remove: u32,
    keep_before: Vec3,
    keep_after: Vec3,
    removed_position: Vec3,
    /// End of this collapse's entries in `Recorder::renamed` and `Recorder::deleted`.
    renamed_end: u32,
    deleted_end: u32,
}

/// Filled by the collapse loop, one [`Recorder::collapse`] per edge collapse: flat arrays,
/// no allocation per collapse (docs/design.md#progressive).
#[derive(Debug, Clone, Default)]
pub struct Recorder {
    collapses: Vec<Collapse>,
    /// Slots whose `remove` corner became `keep`, collapse after collapse.
    renamed: Vec<u32>,
    /// Slots deleted with the edge, and their triangles, collapse after collapse.
    deleted: Vec<(u32, [u32; 3])>,
    /// One entry per collapse when the model has per-vertex colours (normals, texture
    /// coordinates): `keep` before, `keep` after, `remove`.
    colors: Vec<[[f32; 3]; 3]>,
    normals: Vec<[Vec3; 3]>,
    texcoords: Vec<[[f32; 2]; 3]>,
    /// The original model's per-face colours, if it has them (for the faces splits add).
    face_colors: Option<Vec<[f32; 3]>>,
}

/// What the collapse loop knows of one collapse, before it performs it.
#[derive(Debug, Clone, Copy)]
pub struct CollapseRecord<'a> {
    /// The vertex that stays.
    pub keep: u32,
    /// The vertex that goes.
    pub remove: u32,
    /// `keep`'s position before the collapse.
    pub keep_before: Vec3,
    /// `keep`'s position after the collapse.
    pub keep_after: Vec3,
    /// `remove`'s position.
    pub removed_position: Vec3,
    /// `keep` before, `keep` after, `remove`.
    pub colors: Option<[[f32; 3]; 3]>,
    /// Normals, in the order of `colors`, when the model has per-vertex normals.
    pub normals: Option<[Vec3; 3]>,
    /// Texture coordinates, in the order of `colors`, when the model has them per vertex.
    pub texcoords: Option<[[f32; 2]; 3]>,
    /// Triangles whose corner `remove` becomes `keep`.
    pub renamed: &'a [u32],
    /// Triangles the collapse deletes, with their corners.
    pub deleted: &'a [(u32, [u32; 3])],
}

impl Recorder {
    /// A recorder for collapses of `original` (whose per-face colours it keeps).
    pub fn new(original: &Model) -> Self {
        let face_colors = match &original.colors {
            Some(Attribute::PerFace(c)) => Some(c.clone()),
            _ => None,
        };
        Self {
            face_colors,
            ..Self::default()
        }
    }

    /// Records one collapse, in the order the decimator performs them.
    pub fn collapse(&mut self, c: CollapseRecord<'_>) {
        self.renamed.extend_from_slice(c.renamed);
        self.deleted.extend_from_slice(c.deleted);
        self.colors.extend(c.colors);
        self.normals.extend(c.normals);
        self.texcoords.extend(c.texcoords);
        self.collapses.push(Collapse {
            keep: c.keep,
            remove: c.remove,
            keep_before: c.keep_before,
            keep_after: c.keep_after,
            removed_position: c.removed_position,
            renamed_end: self.renamed.len() as u32,
            deleted_end: self.deleted.len() as u32,
        });
    }

    /// The progressive model whose base is `base` — the decimated model exactly as the loop
    /// wrote it back, its vertices `kept` (internal ids, in the base's order) and its faces
    /// the live slots of `conn` ascending. `order` and `faces` map internal vertex ids and
    /// triangle slots to the original model's. Slots must never have been reused (the loop
    /// renames in place).
    pub fn finish(
        self,
        base: Model,
        kept: &[u32],
        conn: &Connectivity,
        order: &[u32],
        faces: &[u32],
    ) -> ProgressiveModel {
        let face_colors = self.face_colors.as_deref();
        let mut pm_vertex = vec![u32::MAX; order.len()];
        let mut vertex_ids = Vec::with_capacity(kept.len() + self.collapses.len());
        number_base(kept, order, &mut pm_vertex, &mut vertex_ids);
        let mut pm_face = vec![u32::MAX; conn.triangles().len()];
        let mut face_ids = Vec::new();
        number_base(conn.alive_ids(), faces, &mut pm_face, &mut face_ids);
        // Attributes are recorded for every collapse or for none.
        let n = self.collapses.len();
        let vertex_colors =
            matches!(base.colors, Some(Attribute::PerVertex(_))) && self.colors.len() == n;
        let normals =
            matches!(base.normals, Some(Attribute::PerVertex(_))) && self.normals.len() == n;
        let texcoords = base.texcoords.is_some() && self.texcoords.len() == n;
        let mut splits = Vec::with_capacity(n);
        for (i, c) in self.collapses.iter().enumerate().rev() {
            let start = |ends: fn(&Collapse) -> u32| {
                i.checked_sub(1)
                    .map_or(0, |p| ends(&self.collapses[p]) as usize)
            };
            let renamed_slots = &self.renamed[start(|c| c.renamed_end)..c.renamed_end as usize];
            let deleted = &self.deleted[start(|c| c.deleted_end)..c.deleted_end as usize];
            let new = vertex_ids.len() as u32;
            pm_vertex[c.remove as usize] = new;
            vertex_ids.push(order[c.remove as usize]);
            let renamed = renamed_slots.iter().map(|&t| pm_face[t as usize]).collect();
            let mut added = Vec::with_capacity(deleted.len());
            let mut added_colors = Vec::new();
            for &(t, tri) in deleted {
                pm_face[t as usize] = face_ids.len() as u32;
                face_ids.push(faces[t as usize]);
                added.push(tri.map(|v| pm_vertex[v as usize]));
                if let Some(fc) = face_colors {
                    added_colors.push(
                        fc.get(faces[t as usize] as usize)
                            .copied()
                            .unwrap_or_default(),
                    );
                }
            }
            // Recorded as keep before, keep after, removed; a split's order is keep
            // coarse (after the collapse), keep fine (before it), new.
            splits.push(VertexSplit {
                keep: pm_vertex[c.keep as usize],
                keep_coarse: c.keep_after,
                keep_fine: c.keep_before,
                position: c.removed_position,
                colors: vertex_colors.then(|| {
                    let [b, a, r] = self.colors[i];
                    [a, b, r]
                }),
                normals: normals.then(|| {
                    let [b, a, r] = self.normals[i];
                    [a, b, r]
                }),
                texcoords: texcoords.then(|| {
                    let [b, a, r] = self.texcoords[i];
                    [a, b, r]
                }),
                renamed,
                added,
                added_colors,
            });
        }
        ProgressiveModel {
            base,
            splits,
            vertex_ids,
            face_ids,
        }
    }
}

/// Numbers the base's vertices (or faces) `internal` in order: `numbering` maps an internal
/// id to its number, `ids` gets each one's original id (`original[internal]`).
fn number_base(
    internal: impl IntoIterator<Item = impl Borrow<u32>>,
    original: &[u32],
    numbering: &mut [u32],
    ids: &mut Vec<u32>,
) {
    for (i, v) in internal.into_iter().enumerate() {
        let v = *v.borrow() as usize;
        numbering[v] = i as u32;
        ids.push(original[v]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decimate::{simplify_scene_progressive, Algorithm, Params, Target};
    use crate::mesh::{measure, shapes, Scene};

    fn progressive(model: Model, percent: f64) -> (Model, ProgressiveModel) {
        let mut scene = Scene {
            models: vec![model],
        };
        let params = Params {
            target: Target::RemovePercent(percent),
            algorithm: Algorithm::Qem,
            ..Params::default()
        };
        let (_, pm) = simplify_scene_progressive(&mut scene, &params, &mut |_| {});
        (
            scene.models.remove(0),
            pm.models
                .into_iter()
                .next()
                .unwrap_or_else(|| panic!("no progressive model")),
        )
    }

    #[test]
    fn refining_all_the_way_gives_the_original_back() {
        let original = shapes::bumpy_sphere(24, 32);
        let (decimated, pm) = progressive(original.clone(), 100.0);
        assert!(pm.validate().is_ok());
        assert_eq!(pm.base, decimated);
        assert_eq!(pm.full_vertex_count(), original.positions.len());
        assert_eq!(pm.full_face_count(), original.triangles.len());
        assert!(decimated.positions.len() < 10);
        let back = pm.original();
        assert_eq!(back.positions, original.positions);
        assert_eq!(back.triangles, original.triangles);
    }

    #[test]
    fn every_level_is_a_valid_mesh_and_moving_down_retraces_moving_up() {
        let original = shapes::cube(6, 2.0);
        let (_, pm) = progressive(original.clone(), 100.0);
        let mut lod = Lod::new(&pm);
        let mut seen = Vec::new();
        for level in 0..=lod.max_level() {
            lod.set_level(level);
            let m = lod.model();
            assert_eq!(m.positions.len(), pm.base.positions.len() + level);
            assert_eq!(measure::degenerate_triangles(m, 1e-9), 0, "level {level}");
            // A closed cube stays closed: every edge on exactly two faces.
            assert_eq!(measure::boundary_loops(m), 0, "level {level}");
            assert_eq!(measure::euler_characteristic(m), 2, "level {level}");
            seen.push(m.clone());
        }
        for level in (0..=lod.max_level()).rev() {
            lod.set_level(level);
            assert_eq!(lod.model(), &seen[level], "level {level} going down");
        }
    }

    /// `m` with texture coordinates `(x, y) / 10` of each vertex's position.
    fn textured(mut m: Model) -> Model {
        m.texcoords = Some(
            m.positions
                .iter()
                .map(|p| [p.x, p.y].map(|c| c * 0.1))
                .collect(),
        );
        m
    }

    #[test]
    fn texture_coordinates_come_back_exactly_and_retrace_every_level() {
        let mut original = shapes::bumpy_sphere(16, 24);
        let uv = |p: &Vec3| [p.x + 0.5 * p.z, p.y];
        original.texcoords = Some(original.positions.iter().map(uv).collect());
        let (decimated, pm) = progressive(original.clone(), 100.0);
        assert!(pm.validate().is_ok());
        assert_eq!(pm.base, decimated);
        assert!(pm.base.texcoords.is_some());
        let back = pm.original();
        assert_eq!(back.positions, original.positions);
        assert_eq!(back.texcoords, original.texcoords);
        let mut lod = Lod::new(&pm);
        let mut seen = Vec::new();
        for level in 0..=lod.max_level() {
            lod.set_level(level);
            let m = lod.model();
            assert_eq!(m.texcoords.as_ref().map(Vec::len), Some(m.positions.len()));
            seen.push(m.texcoords.clone());
        }
        for level in (0..=lod.max_level()).rev() {
            lod.set_level(level);
            assert_eq!(
                lod.model().texcoords,
                seen[level],
                "level {level} going down"
            );
        }
    }

    /// An open, bumpy tube textured by its (angle, height), cut down one side by a texture
    /// seam: the columns at u = 0 and u = 1 are the same points, once per side.
    fn seamed_tube(around: u32, along: u32) -> Model {
        let (mut positions, mut texcoords, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
        for j in 0..=along {
            for i in 0..=around {
                let (u, v) = ((i % around) as f32 / around as f32, j as f32 / along as f32);
                let angle = std::f32::consts::TAU * u;
                let r = 1.0 + 0.1 * (3.0 * angle).sin() * (4.0 * v).cos();
                positions.push(Vec3::new(r * angle.cos(), r * angle.sin(), v));
                texcoords.push([i as f32 / around as f32, v]);
            }
        }
        let id = |i: u32, j: u32| j * (around + 1) + i;
        for j in 0..along {
            for i in 0..around {
                let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        Model {
            positions,
            triangles,
            texcoords: Some(texcoords),
            ..Model::default()
        }
    }

    #[test]
    fn a_seam_collapsed_on_both_sides_never_shows_one_side_alone() {
        let (_, pm) = progressive(seamed_tube(24, 12), 100.0);
        assert!(pm.validate().is_ok());
        // The points of each side of the seam (u = 0 and u = 1) at `level`: equal sets when
        // the seam is closed.
        let sides = |level: usize| {
            let mut lod = Lod::new(&pm);
            lod.set_level(level);
            let m = lod.model();
            let t = m.texcoords.clone().unwrap_or_default();
            let side = |u: f32| {
                let mut points: Vec<[u32; 3]> = m
                    .positions
                    .iter()
                    .zip(&t)
                    .filter(|(_, uv)| uv[0] == u)
                    .map(|(p, _)| p.to_array().map(f32::to_bits))
                    .collect();
                points.sort_unstable();
                points
            };
            (side(0.0), side(1.0))
        };
        let mut halves = 0;
        for level in 0..=pm.splits.len() {
            let whole = pm.whole_level(level);
            let (a, b) = sides(whole);
            assert_eq!(a, b, "level {level} (shown as {whole}): the seam parts");
            if whole != level {
                halves += 1;
                let (a, b) = sides(level);
                assert_ne!(a, b, "level {level}: half a seam collapse");
            }
        }
        // The seam went down in pairs: levels between a pair's splits exist.
        assert!(halves > 3, "{halves} seam pairs");
    }

    #[test]
    fn a_flat_grid_keeps_its_mapping_at_every_level() {
        let (_, pm) = progressive(textured(shapes::test003()), 100.0);
        let mut lod = Lod::new(&pm);
        for level in 0..=lod.max_level() {
            lod.set_level(level);
            let m = lod.model();
            let t = m.texcoords.as_deref().unwrap_or_default();
            assert_eq!(t.len(), m.positions.len(), "level {level}");
            for (p, uv) in m.positions.iter().zip(t) {
                let want = [p.x, p.y].map(|c| c * 0.1);
                let off = (uv[0] - want[0]).abs().max((uv[1] - want[1]).abs());
                assert!(off < 1e-5, "level {level}: {p} maps to {uv:?}");
            }
        }
    }

    #[test]
    fn geomorph_starts_where_the_coarse_level_is() {
        let (_, pm) = progressive(shapes::bumpy_sphere(12, 16), 100.0);
        let mut lod = Lod::new(&pm);
        lod.set_level(20);
        let coarse: Vec<Vec3> = lod.model().positions.clone();
        let coarse_tris = lod.model().triangles.clone();
        lod.set_level(60);
        let start = lod.positions_at(20);
        assert_eq!(start.len(), lod.model().positions.len());
        // Vertices that exist at level 20 start at their level-20 positions...
        assert_eq!(&start[..coarse.len()], &coarse[..]);
        // ...and the fine mesh drawn at the start positions covers the coarse one: every
        // fine triangle at its start positions is either collapsed flat or one of the coarse
        // triangles.
        let key = |t: [Vec3; 3]| {
            let mut k: Vec<[u32; 3]> = t.iter().map(|p| p.to_array().map(f32::to_bits)).collect();
            k.sort();
            k
        };
        let coarse_keys: std::collections::HashSet<_> = coarse_tris
            .iter()
            .map(|t| key(t.map(|v| coarse[v as usize])))
            .collect();
        for t in &lod.model().triangles {
            let p = t.map(|v| start[v as usize]);
            let flat = p[0] == p[1] || p[1] == p[2] || p[0] == p[2];
            assert!(flat || coarse_keys.contains(&key(p)));
        }
    }
}
