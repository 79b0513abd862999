//! The Rapier scene built from a scenario: a ground slab, fixed cuboids for static structures,
//! kinematic position-based cuboids for the actors and the ego car. Moving the scene to an instant
//! teleports every kinematic body to its exact pose and commits the poses with
//! `CollisionPipeline::step`, which refreshes colliders and the broad-phase BVH without dynamics,
//! then refits the lidar's ray-cast tree.

use rapier3d::prelude::*;

use super::actor_tree::ActorTree;
use super::collider_tables::{ColliderTables, MoverPart, StreetCollider};
use super::ray_tree::RayTree;
use super::{SceneActor, Surface};
use crate::error::{Result, SimError};
use crate::motion::MotionState;
use crate::scenario::{ActorConfig, Scenario, drawn_bodies};
use crate::world::StreetWorld;

/// Half size of the square ground slab, metres (scenarios keep the ego on it).
const GROUND_HALF_M: f32 = crate::scenario::GROUND_HALF_M as f32;

/// Rapier sets and pipelines plus the actor and surface tables.
pub struct Scene {
    pub(super) bodies: RigidBodySet,
    pub(super) colliders: ColliderSet,
    pub(super) broad_phase: BroadPhaseBvh,
    pub(super) narrow_phase: NarrowPhase,
    islands: IslandManager,
    collision_pipeline: CollisionPipeline,
    params: IntegrationParameters,
    pub(super) surfaces: Vec<Surface>,
    surface_of_collider: Vec<u32>,
    pub(super) actors: Vec<SceneActor>,
    actor_states: Vec<MotionState>,
    pub(super) ego: SceneActor,
    /// The moving colliders, ego car first (see [`MoverPart`]).
    pub(super) movers: Vec<MoverPart>,
    pub(super) ray_tree: RayTree,
    /// The lidar's tree over the actors, in a street world (see [`ActorTree`]).
    pub(super) actor_tree: ActorTree,
    /// The street world (`None`: the world of the first release, every collider in the tree).
    pub(super) street: Option<StreetCollider>,
}

impl Scene {
    /// Builds the scene of a validated scenario; `actors` are its actors plus any random traffic.
    /// The `ideal` world is the ground slab, boxes for structures and actors; otherwise the
    /// street world drawn from `seed` (`StreetWorld`).
    pub fn build(scenario: &Scenario, actors: &[ActorConfig]) -> Result<Self> {
        Self::build_seeded(scenario, actors, 0)
    }

    /// [`Scene::build`] with the street world drawn from `seed`.
    pub fn build_seeded(scenario: &Scenario, actors: &[ActorConfig], seed: u64) -> Result<Self> {
        let knobs = scenario.world.knobs();
        let street_world = knobs != crate::WorldKnobs::of(crate::Realism::Ideal);
        let (actors, bodies) = drawn_bodies(actors, knobs.fleet, seed, &scenario.name);
        let actors = actors.as_slice();
        let mut tables = ColliderTables::default();
        let mut street = None;
        if street_world {
            let world = StreetWorld::build(scenario, actors, seed);
            if world.ground.is_none() {
                let ground =
                    ColliderTables::ground(GROUND_HALF_M, scenario.ground_reflectivity as f32);
                tables.add_fixed(ground, Pose::translation(0.0, 0.0, -0.5), 0.0);
            }
            street = Some(tables.add_street(world.ground, &world.pieces));
        } else {
            let ground = ColliderTables::ground(GROUND_HALF_M, scenario.ground_reflectivity as f32);
            tables.add_fixed(ground, Pose::translation(0.0, 0.0, -0.5), 0.0);
            add_structure_boxes(&mut tables, scenario);
        }
        let ego = tables
            .add_actor(&scenario.ego, (0, None), false, None)
            .map_err(|r| invalid(scenario, r))?;
        let mut scene_actors = Vec::with_capacity(actors.len());
        for (i, config) in actors.iter().enumerate() {
            let id = u16::try_from(i + 1)
                .map_err(|_| invalid(scenario, "more than 65535 actors".to_owned()))?;
            let actor = tables
                .add_actor(
                    config,
                    (id, Some(i)),
                    knobs.shapes,
                    bodies[i].map(|b| b.belt_m),
                )
                .map_err(|r| invalid(scenario, r))?;
            scene_actors.push(actor);
        }
        let moving = tables.movers.iter().map(|m| m.handle).collect();
        let ray_tree = RayTree::new(&tables.colliders, moving);
        let actor_tree = ActorTree::new(&tables.movers);
        let mut scene = Self {
            bodies: tables.bodies,
            colliders: tables.colliders,
            broad_phase: BroadPhaseBvh::new(),
            narrow_phase: NarrowPhase::new(),
            islands: IslandManager::new(),
            collision_pipeline: CollisionPipeline::new(),
            params: IntegrationParameters::default(),
            surfaces: tables.surfaces,
            surface_of_collider: tables.surface_of_collider,
            actor_states: Vec::with_capacity(scene_actors.len()),
            actors: scene_actors,
            ego,
            movers: tables.movers,
            ray_tree,
            actor_tree,
            street,
        };
        scene.move_to(scenario.start_secs);
        scene.rebuild_ray_tree();
        Ok(scene)
    }

    /// Moves every actor and the ego car to its exact pose at `t_secs` and commits the poses to
    /// the colliders and the BVH, so ray casts see the scene at that instant. The actors' motion
    /// states at `t_secs` are kept for labelling ([`Scene::actor_states`]).
    pub fn move_to(&mut self, t_secs: f64) {
        self.actor_states.clear();
        self.actor_states
            .extend(self.actors.iter().map(|a| a.trajectory.state_at(t_secs)));
        let ego_state = self.ego.trajectory.state_at(t_secs);
        let moves = std::iter::once((&self.ego, &ego_state))
            .chain(self.actors.iter().zip(&self.actor_states));
        for (actor, state) in moves {
            if let Some(body) = self.bodies.get_mut(actor.body) {
                body.set_position(actor.pose_of(state), false);
            }
        }
        for part in &self.movers {
            let (actor, state) = match part.actor {
                Some(i) => (&self.actors[i], &self.actor_states[i]),
                None => (&self.ego, &ego_state),
            };
            let pose = actor.pose_of(state) * part.relative;
            if let Some(surface) = self.surfaces.get_mut(part.surface) {
                surface.place(pose.translation, state.yaw_rad as f32);
            }
        }
        self.collision_pipeline.step(
            self.params.prediction_distance(),
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &(),
            &(),
        );
        self.ray_tree.refit_moving(&self.colliders);
    }

    /// The surface a collider stands for, placed as the scene was last moved (one array read).
    #[inline]
    pub fn surface(&self, handle: ColliderHandle) -> Option<&Surface> {
        self.surface_at(handle.into_raw_parts().0)
    }

    /// The surface of the collider at arena index `index` (a leaf index of the ray-cast tree).
    #[inline]
    pub(super) fn surface_at(&self, index: u32) -> Option<&Surface> {
        let surface = *self.surface_of_collider.get(index as usize)?;
        self.surfaces.get(surface as usize)
    }

    /// Motion state of every actor at the instant the scene was last moved, in actor order.
    pub fn actor_states(&self) -> &[MotionState] {
        &self.actor_states
    }

    /// The moving actors, in instance-id order.
    pub fn actors(&self) -> &[SceneActor] {
        &self.actors
    }

    /// The ego car.
    pub fn ego(&self) -> &SceneActor {
        &self.ego
    }

    /// Number of colliders (ground, structures, actors, ego).
    pub fn collider_count(&self) -> usize {
        self.colliders.len()
    }

    /// Number of static pieces inside the street world's one collider (0 on the `ideal` world).
    pub fn street_piece_count(&self) -> usize {
        self.street.as_ref().map_or(0, |s| s.shape.pieces().len())
    }

    /// The velocity Rapier itself derives for actor `index` arriving at its pose at `t_secs` from
    /// its pose at `t_secs − dt_secs` (a backward difference over one physics step); returns
    /// (linear velocity, angular velocity about z). The scene is left at `t_secs`.
    pub fn rapier_velocity(
        &mut self,
        index: usize,
        t_secs: f64,
        dt_secs: f64,
    ) -> Option<([f64; 3], f64)> {
        let actor = self.actors.get(index)?.clone();
        let before = actor.pose_of(&actor.trajectory.state_at(t_secs - dt_secs));
        let state = actor.trajectory.state_at(t_secs);
        let after = actor.pose_of(&state);
        self.bodies.get_mut(actor.body)?.set_position(before, true);
        self.bodies
            .get_mut(actor.body)?
            .set_next_kinematic_position(after);
        let mut params = self.params;
        params.dt = dt_secs as f32;
        PhysicsPipeline::new().step(
            Vector::ZERO,
            &params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut ImpulseJointSet::new(),
            &mut MultibodyJointSet::new(),
            &mut SoftBodySet::new(),
            &mut CCDSolver::new(),
            &(),
            &(),
        );
        // Keep the lidar's tables in step with the colliders that moved.
        for part in self.movers.iter().filter(|m| m.actor == Some(index)) {
            let pose = after * part.relative;
            self.surfaces
                .get_mut(part.surface)?
                .place(pose.translation, state.yaw_rad as f32);
        }
        *self.actor_states.get_mut(index)? = state;
        self.ray_tree.refit_moving(&self.colliders);
        let body = self.bodies.get(actor.body)?;
        let (v, w) = (body.linvel(), body.angvel());
        Some((
            [f64::from(v.x), f64::from(v.y), f64::from(v.z)],
            f64::from(w.z),
        ))
    }
}

/// The scenario's structures as fixed boxes standing on z = 0 (the world of the first release).
fn add_structure_boxes(tables: &mut ColliderTables, scenario: &Scenario) {
    for structure in &scenario.structures {
        let size = structure.size_m.unwrap_or(structure.kind.default_size());
        let surface = Surface::new(
            structure.kind.semantic(),
            None,
            [
                size[0] as f32 / 2.0,
                size[1] as f32 / 2.0,
                size[2] as f32 / 2.0,
            ],
            structure.reflectivity.unwrap_or(0.5) as f32,
        );
        let yaw_rad = structure.yaw_deg.to_radians() as f32;
        for c in structure.centres_m() {
            let pose = Pose::new(
                Vector::new(c[0] as f32, c[1] as f32, size[2] as f32 / 2.0),
                Vector::new(0.0, 0.0, yaw_rad),
            );
            tables.add_fixed(surface, pose, yaw_rad);
        }
    }
}

fn invalid(scenario: &Scenario, reason: String) -> SimError {
    SimError::Options(format!("scenario {}: {reason}", scenario.name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_analytic_velocity_equals_the_velocity_rapier_derives() {
        let text = "realism = \"ideal\"\nsweeps = 1\n[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 3.0\n[[actors]]\nname = \"turner\"\npath_m = [[0.0, 10.0], [20.0, 10.0], [20.0, 40.0]]\nturn_radius_m = 6.0\nspeed_mps = 8.0\ninitial_speed_mps = 2.0\n";
        let scenario = Scenario::from_toml(text, "turn.toml", "turn").unwrap();
        let mut scene = Scene::build(&scenario, &scenario.actors).unwrap();
        let dt = 0.01;
        let mut turning_samples = 0;
        for i in 0..40 {
            let t = 0.1 * f64::from(i);
            let (v, w) = scene.rapier_velocity(0, t, dt).unwrap();
            // Rapier's velocity is the backward difference over [t − dt, t]: the analytic value
            // at the middle of that step, up to O(dt²) and f32 rounding of the poses.
            let truth = scene.actors()[0].trajectory.state_at(t - dt / 2.0);
            assert!(
                (v[0] - truth.velocity_mps[0]).abs() < 0.02
                    && (v[1] - truth.velocity_mps[1]).abs() < 0.02,
                "t = {t}: rapier {v:?}, truth {:?}",
                truth.velocity_mps
            );
            let before = scene.actors()[0].trajectory.state_at(t - dt);
            if (before.yaw_rate_radps - truth.yaw_rate_radps).abs() < 1e-9
                && scene.actors()[0].trajectory.state_at(t).yaw_rate_radps == truth.yaw_rate_radps
            {
                assert!(
                    (w - truth.yaw_rate_radps).abs() < 0.01,
                    "t = {t}: rapier ω {w}, truth {}",
                    truth.yaw_rate_radps
                );
                turning_samples += usize::from(truth.yaw_rate_radps.abs() > 0.1);
            }
        }
        assert!(turning_samples > 0, "the test never sampled the arc");
    }
}
