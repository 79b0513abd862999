//! A user's own vehicle model: a Wavefront OBJ file named by an actor's `mesh` (its path relative
//! to the scenario file), read with `tobj` (faces triangulated, materials ignored), checked
//! (not empty, at most [`MAX_MESH_TRIANGLES`] triangles, finite coordinates, a solid extent on
//! every axis, some triangle with an area) and kept in its own frame. The scene scales it to the
//! actor's `size_m` box; the truth stays that box.

use std::path::{Path, PathBuf};

use super::Scenario;
use super::problem::{Problem, Seg};

/// Most triangles one vehicle mesh may have: a detailed car model has a few thousand; far more
/// only slows the ray casts down without changing what a 0.1° beam sees.
pub const MAX_MESH_TRIANGLES: usize = 20_000;

/// Largest OBJ file read, bytes (20,000 triangles take well under 2 MB of text).
const MAX_MESH_BYTES: u64 = 8 << 20;

/// A triangle mesh read from an OBJ file, in the file's own frame and units.
#[derive(Debug, Clone, PartialEq)]
pub struct VehicleMesh {
    /// The file it was read from.
    pub source: PathBuf,
    /// Vertex positions.
    pub vertices: Vec<[f32; 3]>,
    /// Triangles as indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
}

impl VehicleMesh {
    /// Reads and checks the OBJ file at `path`; the error says what is wrong with it (the caller
    /// names the file and the scenario line).
    ///
    /// ```
    /// let dir = tempfile::tempdir().unwrap(); // removed when it goes out of scope
    /// let path = dir.path().join("wedge.obj");
    /// std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n").unwrap();
    /// let mesh = patchflow_sim::VehicleMesh::load(&path).unwrap();
    /// assert_eq!(mesh.triangles.len(), 4);
    /// ```
    pub fn load(path: &Path) -> Result<Self, String> {
        let bytes = patchflow_dataset::read_limited(path, MAX_MESH_BYTES).map_err(|e| {
            match (std::fs::metadata(path), e) {
                (Err(io), _) if io.kind() == std::io::ErrorKind::NotFound => {
                    "no such file".to_owned()
                }
                (_, patchflow_dataset::DatasetError::NotRegular { what, .. }) => what,
                (_, e) => format!("cannot be read ({e})"),
            }
        })?;
        // Editors on Windows start UTF-8 files with a byte-order mark; it is no OBJ statement.
        let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(&bytes);
        let options = tobj::LoadOptions {
            triangulate: true,
            single_index: false,
            ignore_points: true,
            ignore_lines: true,
        };
        let (models, _) = tobj::load_obj_buf(&mut &bytes[..], &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(|e| format!("is not a readable OBJ file ({e})"))?;
        let mut vertices = Vec::new();
        let mut triangles = Vec::new();
        for model in &models {
            let base = vertices.len() as u32;
            vertices.extend(
                model
                    .mesh
                    .positions
                    .chunks_exact(3)
                    .map(|p| [p[0], p[1], p[2]]),
            );
            triangles.extend(
                model
                    .mesh
                    .indices
                    .chunks_exact(3)
                    .map(|t| [base + t[0], base + t[1], base + t[2]]),
            );
            if triangles.len() > MAX_MESH_TRIANGLES {
                break;
            }
        }
        let mesh = Self {
            source: path.to_owned(),
            vertices,
            triangles,
        };
        mesh.check()?;
        Ok(mesh)
    }

    /// SHA-256 (hex) of the geometry the simulator uses: every vertex's bits and every
    /// triangle's indices. `generate` records it beside the resolved scenario text, so an edited
    /// mesh file makes another request rather than being mixed into a dataset made with the old.
    pub fn geometry_sha256(&self) -> String {
        let mut bytes = Vec::with_capacity(12 * (self.vertices.len() + self.triangles.len()));
        for v in &self.vertices {
            bytes.extend(v.iter().flat_map(|c| c.to_bits().to_le_bytes()));
        }
        for t in &self.triangles {
            bytes.extend(t.iter().flat_map(|i| i.to_le_bytes()));
        }
        patchflow_dataset::sha256_hex(&bytes)
    }

    /// Why the mesh cannot stand for a vehicle, if it cannot.
    fn check(&self) -> Result<(), String> {
        if self.triangles.is_empty() {
            return Err("has no faces (an empty mesh)".to_owned());
        }
        if self.triangles.len() > MAX_MESH_TRIANGLES {
            return Err(format!(
                "has more than {MAX_MESH_TRIANGLES} triangles; simplify the model"
            ));
        }
        if self.vertices.iter().flatten().any(|c| !c.is_finite()) {
            return Err("has a vertex that is not a finite number".to_owned());
        }
        let (lo, hi) = self.bounds();
        let extent = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        let largest = extent.iter().cloned().fold(0.0f32, f32::max);
        if largest <= 0.0 || extent.iter().any(|&e| e <= 1e-3 * largest) {
            return Err(format!(
                "is degenerate: it is flat or a point (extent {:.3} × {:.3} × {:.3})",
                extent[0], extent[1], extent[2]
            ));
        }
        let has_area = self.triangles.iter().any(|t| {
            let [a, b, c] = t.map(|i| self.vertices[i as usize]);
            let (u, v) = (sub(b, a), sub(c, a));
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt() > 1e-9 * largest * largest
        });
        if !has_area {
            return Err("is degenerate: no triangle has an area".to_owned());
        }
        Ok(())
    }

    /// Smallest and largest vertex coordinates.
    pub fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        self.vertices
            .iter()
            .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), v| {
                (
                    [lo[0].min(v[0]), lo[1].min(v[1]), lo[2].min(v[2])],
                    [hi[0].max(v[0]), hi[1].max(v[1]), hi[2].max(v[2])],
                )
            })
    }

    /// The vertices scaled and moved so that the mesh's bounding box is the actor's box of
    /// `size_m` (length along x, width along y, height along z) centred on the origin.
    pub fn fitted_to(&self, size_m: [f64; 3]) -> Vec<[f32; 3]> {
        let (lo, hi) = self.bounds();
        let scale: [f32; 3] =
            std::array::from_fn(|a| size_m[a] as f32 / (hi[a] - lo[a]).max(f32::MIN_POSITIVE));
        self.vertices
            .iter()
            .map(|v| std::array::from_fn(|a| (v[a] - (lo[a] + hi[a]) / 2.0) * scale[a]))
            .collect()
    }
}

impl Scenario {
    /// Reads every actor's `mesh` file (relative to `base`); a problem names the mesh file.
    pub(super) fn load_meshes(&mut self, base: &Path) -> std::result::Result<(), Problem> {
        if self.ego.mesh.is_some() {
            let reason = "the ego car cannot have a mesh (its own lidar never sees its body)";
            return Err((vec![Seg::Key("ego"), Seg::Key("mesh")], reason.to_owned()));
        }
        for (i, actor) in self.actors.iter_mut().enumerate() {
            let Some(mesh) = &actor.mesh else {
                continue;
            };
            let path = base.join(mesh);
            let loaded = VehicleMesh::load(&path).map_err(|reason| {
                let at = vec![Seg::Key("actors"), Seg::Index(i), Seg::Key("mesh")];
                (
                    at,
                    format!("{}: mesh {}: {reason}", actor.name, path.display()),
                )
            })?;
            actor.mesh_data = Some(std::sync::Arc::new(loaded));
        }
        Ok(())
    }
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
#[path = "vehicle_mesh_tests.rs"]
mod tests;
