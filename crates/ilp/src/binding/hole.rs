//! Holes (thesis §4.1, fig. 4.2): a `holeInSurface` object becomes an aperture through
//! which rays pass, by giving its instances a copy of their mesh whose every triangle
//! is of a hole material (the tracer makes the object's box a volume where every
//! surface is transparent).

use invlight_scene::{Material, Scene, SurfaceId};

/// Gives a surface's instances a copy of their mesh whose every triangle is a hole.
pub fn make_hole(scene: &mut Scene, s: SurfaceId, id: &str) {
    let mut hole = None;
    for i in scene.surfaces[s as usize].instances.clone() {
        let mesh = scene.instances[i as usize].mesh as usize;
        if scene.meshes[mesh]
            .materials
            .iter()
            .all(|&m| scene.materials[m as usize].hole)
        {
            continue;
        }
        let h = *hole
            .get_or_insert_with(|| scene.add_material(Material::hole(&format!("{id} (hole)"))));
        let mut copy = scene.meshes[mesh].clone();
        copy.materials.iter_mut().for_each(|m| *m = h);
        scene.instances[i as usize].mesh = scene.add_mesh(copy);
    }
}
