//! What the texture tests compare: a scene's triangle corners with their coordinates.

use decimate_core::mesh::Scene;

/// Each triangle corner as (position bits, texture coordinate bits): what a round trip must
/// keep exactly, whatever order the vertices come back in.
pub fn textured_corners(s: &Scene) -> Vec<[u32; 5]> {
    let mut v = Vec::new();
    for m in &s.models {
        let t = m.texcoords.as_ref().expect("texture coordinates");
        assert_eq!(t.len(), m.positions.len());
        for tri in &m.triangles {
            for &i in tri {
                let (p, uv) = (m.positions[i as usize], t[i as usize]);
                v.push([p.x, p.y, p.z, uv[0], uv[1]].map(f32::to_bits));
            }
        }
    }
    v
}
