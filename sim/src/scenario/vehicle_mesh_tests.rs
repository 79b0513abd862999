//! Tests of [`VehicleMesh`]: loading, every rejection, and the fit to an actor's box.

use super::*;

/// A unit cube with quad faces (12 triangles once triangulated), 2 × 1 × 1 units.
const BOX_OBJ: &str = "o box\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 1\nv 2 0 1\nv 2 1 1\nv 0 1 1\n\
f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";

fn write(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

#[test]
fn a_quad_mesh_loads_as_triangles() {
    let (_dir, path) = write("box.obj", BOX_OBJ);
    let mesh = VehicleMesh::load(&path).unwrap();
    assert_eq!(mesh.vertices.len(), 8);
    assert_eq!(mesh.triangles.len(), 12);
}

#[test]
fn the_fitted_mesh_spans_the_actor_box_centred_on_the_origin() {
    let (_dir, path) = write("box.obj", BOX_OBJ);
    let fitted = VehicleMesh::load(&path).unwrap().fitted_to([5.0, 2.0, 1.8]);
    for (a, half) in [2.5f32, 1.0, 0.9].into_iter().enumerate() {
        let lo = fitted.iter().map(|v| v[a]).fold(f32::MAX, f32::min);
        let hi = fitted.iter().map(|v| v[a]).fold(f32::MIN, f32::max);
        assert!(
            (lo + half).abs() < 1e-5 && (hi - half).abs() < 1e-5,
            "axis {a}: {lo}..{hi}"
        );
    }
}

#[test]
fn a_missing_file_is_named_as_missing() {
    let err = VehicleMesh::load(Path::new("/nonexistent/van.obj")).unwrap_err();
    assert!(err.contains("no such file"), "{err}");
}

#[test]
fn an_empty_mesh_is_rejected() {
    let (_dir, path) = write("empty.obj", "# nothing here\nv 0 0 0\n");
    let err = VehicleMesh::load(&path).unwrap_err();
    assert!(err.contains("no faces"), "{err}");
}

#[test]
fn a_flat_mesh_is_rejected_as_degenerate() {
    let (_dir, path) = write(
        "flat.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    );
    let err = VehicleMesh::load(&path).unwrap_err();
    assert!(err.contains("degenerate"), "{err}");
}

#[test]
fn a_mesh_whose_triangles_have_no_area_is_rejected_as_degenerate() {
    let (_dir, path) = write(
        "line.obj",
        "v 0 0 0\nv 1 1 1\nv 2 2 2\nv 0 0 0\nf 1 2 3\nf 1 3 2\n",
    );
    let err = VehicleMesh::load(&path).unwrap_err();
    assert!(err.contains("degenerate"), "{err}");
}

#[test]
fn a_mesh_with_too_many_triangles_is_rejected() {
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n");
    for _ in 0..=MAX_MESH_TRIANGLES {
        text.push_str("f 1 2 4\n");
    }
    let (_dir, path) = write("big.obj", &text);
    let err = VehicleMesh::load(&path).unwrap_err();
    assert!(err.contains("more than"), "{err}");
}

#[test]
fn a_file_that_is_not_obj_is_rejected_as_unreadable() {
    let (_dir, path) = write("bad.obj", "v 0 zero 0\nf 1 2 3\n");
    let err = VehicleMesh::load(&path).unwrap_err();
    assert!(err.contains("not a readable OBJ"), "{err}");
}

#[test]
fn the_shipped_van_loads_within_the_triangle_bound() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/meshes/van.obj");
    let mesh = VehicleMesh::load(&path).unwrap();
    assert!(
        (100..=1000).contains(&mesh.triangles.len()),
        "{}",
        mesh.triangles.len()
    );
}

/// A one-sweep scene whose target van stands 8 m ahead on the left lane, in `dir`, drawn from
/// `mesh` if given.
fn van_scene(dir: &Path, mesh: Option<&str>) -> crate::Simulation {
    let mesh_line = mesh.map_or(String::new(), |m| format!("mesh = \"{m}\"\n"));
    let text = format!(
        "sweeps = 1\n[lidar]\nchannels = 32\nazimuth_steps = 720\nblocks = 36\n[ego]\npath_m = [[0.0, -1.75], [50.0, -1.75]]\nspeed_mps = 0.0\n[[actors]]\nname = \"van\"\ntarget = true\nmodel = \"van\"\n{mesh_line}path_m = [[8.0, 1.75], [9.0, 1.75]]\nspeed_mps = 0.0\n"
    );
    let path = dir.join("van_scene.toml");
    std::fs::write(&path, text).unwrap();
    let scenario = crate::Scenario::from_file(&path).unwrap();
    crate::Simulation::new(&scenario, 1).unwrap()
}

#[test]
fn a_meshed_van_is_hit_on_its_mesh_and_keeps_its_box_as_truth() {
    let dir = tempfile::tempdir().unwrap();
    let van = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/meshes/van.obj");
    std::fs::create_dir_all(dir.path().join("meshes")).unwrap();
    std::fs::copy(&van, dir.path().join("meshes/van.obj")).unwrap();
    let on_van = |sweep: &patchflow_dataset::Sweep| {
        (0..sweep.len())
            .filter(|&i| sweep.labels[i].instance() == 1)
            .map(|i| sweep.points_in_sensor[i])
            .collect::<Vec<_>>()
    };
    let meshed = van_scene(dir.path(), Some("meshes/van.obj")).sweep(0);
    let compound = van_scene(dir.path(), None).sweep(0);
    let (meshed_points, compound_points) = (on_van(&meshed), on_van(&compound));
    assert!(
        meshed_points.len() > 100,
        "{} points on the meshed van",
        meshed_points.len()
    );
    assert_ne!(
        meshed_points, compound_points,
        "the mesh is what the beams hit"
    );
    let truth = meshed.target().unwrap();
    // On `urban` the van's box is drawn from the fleet (seed 1, the scenario, the actor).
    let drawn = crate::scenario::VehicleBody::draw(
        patchflow_dataset::ActorClass::Car,
        Some(crate::scenario::CarModel::Van),
        crate::scenario::fleet_key(1, "van_scene", "van"),
    )
    .unwrap();
    assert_eq!(truth.size_m, drawn.size_m, "the truth stays the van's box");
    // Every hit lies inside the box; tolerance 15 cm: range noise (2 cm, 3 sigma), the drifting
    // ego pose estimate the points are written with, and calibration error.
    let pose = meshed.world_from_sensor;
    for p in &meshed_points {
        let w = pose * nalgebra::Point3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
        assert!((w.x - truth.centre_m[0]).abs() < 2.55 + 0.15, "{w:?}");
        assert!((w.y - truth.centre_m[1]).abs() < 0.975 + 0.15, "{w:?}");
    }
}

#[test]
fn a_broken_mesh_names_the_mesh_file_and_the_scenario_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.toml");
    std::fs::write(
        &path,
        "sweeps = 1\n[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 5.0\n[[actors]]\nname = \"van\"\npath_m = [[8.0, 3.5], [9.0, 3.5]]\nspeed_mps = 0.0\nmesh = \"missing.obj\"\n",
    )
    .unwrap();
    let err = crate::Scenario::from_file(&path).unwrap_err().to_string();
    assert!(err.contains("broken.toml:9:"), "{err}");
    assert!(
        err.contains("missing.obj") && err.contains("no such file"),
        "{err}"
    );
}

#[test]
fn a_mesh_starting_with_a_utf8_byte_order_mark_loads() {
    // Without the mark stripped, the first vertex line is not read and face 8 is out of bounds.
    let text = format!("\u{feff}{}", BOX_OBJ.trim_start_matches("o box\n"));
    let (_dir, path) = write("bom.obj", &text);
    let mesh = VehicleMesh::load(&path).unwrap();
    assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (8, 12));
}

#[test]
fn a_fifo_given_as_a_mesh_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("van.obj");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        return; // no mkfifo here: nothing to test
    }
    let err = VehicleMesh::load(&fifo).unwrap_err();
    assert!(err.contains("not a regular file"), "{err}");
}
