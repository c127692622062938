"""Spawn and delete of Gazebo's world API: a model (SDF, or a plain URDF converted to SDF as
Gazebo converts it: spawn_request) or a robot (a URDF with plugins) built in the world, in
three steps (spawn_pose, prepare_spawn, spawn_prepared), and removed; a deleted model's bodies
are parked for the next spawn of the same text (body_pool.BodyPool: pybullet frees little of a
removed body)."""
import os
from typing import List

from ...errors import RequestError
from ..engine.bullet_shapes import ShapeBudgetError
from ..engine.world_bullet import build_world, place_world_bodies, reused_world_bodies
from . import reference_frames as rf
from .reference_frames import Pose
from .request_checks import check_names
from .spawn_request import SpawnRequest, placed, prepare_spawn
from .world_models import (ENTITY_EXISTS, SPAWN_FAILURE, check_model_name, models_of_world,
                           spawn_failure)


class SpawnRequests:
    """The spawn and delete requests of the world API (its ``_spawned``: each spawned model's
    text and bodies, for delete to park).

    A part of ``WorldControl`` (world_control), which gives it ``sim``, ``models`` and the
    shared look-ups (``_model``, ``_frame``, ``_scoped_link``, ``_joint``)."""

    def spawn(self, name: str, xml: str, pose: Pose, reference: str = "",
              kind: str = "sdf", robot_namespace: str = "") -> List[str]:
        """Add model ``name`` built from ``xml`` at ``pose`` (in ``reference``); a robot URDF
        (one with plugins) becomes a robot whose topics and frames are in ``robot_namespace``.
        The three steps at once: the world API runs the middle one outside the loop. Returns
        the building's warning lines (spawn_prepared)."""
        pose = self.spawn_pose(name, pose, reference, robot_namespace)
        request = prepare_spawn(name, xml, pose, kind, robot_namespace=robot_namespace)
        return self.spawn_prepared(request, pose, robot_namespace)

    def spawn_pose(self, name: str, pose: Pose, reference: str = "",
                   robot_namespace: str = "") -> Pose:
        """Step 1, in the loop (quick): the checks of a spawn's names, and the world pose of
        ``pose`` in ``reference``. RequestError (Gazebo's status text) if it cannot be."""
        check_names(SPAWN_FAILURE, model_name=name, reference_frame=reference,
                    robot_namespace=robot_namespace)
        check_model_name(name)
        if name in self.models:
            raise RequestError(ENTITY_EXISTS)
        if not rf.is_world_frame(reference):
            try:
                frame = self.models.frame(reference)[0]
            except KeyError:
                raise spawn_failure("reference reference_frame %r not found, or it is not a "
                                    "model or a scoped link" % reference) from None
        else:
            frame = None
        try:
            return placed(pose, frame)
        except ValueError as err:
            raise spawn_failure(str(err)) from None

    def spawn_prepared(self, request: SpawnRequest, pose: Pose,
                       robot_namespace: str = "") -> List[str]:
        """Step 3, in the loop: build what ``spawn_request.prepare_spawn`` read and checked
        (step 2, anywhere) at world ``pose``: bounded work, the pybullet calls only. Returns
        the building's warning lines (an SDF model's textures that the texture budget halved
        or that cannot be read now; what a plain URDF left out, RobotDescription.warnings,
        and what its conversion warns of: a robot's are its own, SimRobot.warnings), for the
        caller to log."""
        name = request.name
        if name in self.models:       # taken since step 1
            raise RequestError(ENTITY_EXISTS)
        client = self.sim.physics.client
        warnings: List[str] = []
        if request.robot is not None:
            self._add_robot(request, pose, robot_namespace)
            return warnings
        pool = self.sim.physics.body_pool
        key = self._pool_key(request)
        reused = pool.take(key)
        if reused is not None:
            bodies = reused_world_bodies(request.world, reused)
            place_world_bodies(request.world, bodies, client)
        else:
            try:
                bodies = build_world(request.world, client, warnings)
            except ShapeBudgetError as err:
                raise spawn_failure(str(err)) from None
            pool.remember(list(bodies.values()))
        model = models_of_world(request.world, bodies, client)[0]
        built = list(dict.fromkeys(bodies.values()))
        if request.description is not None:
            warnings[:0] = list(request.description.warnings) + list(request.notes)
        self.models.add(model)
        self._spawned[name] = (key, built)
        return warnings

    def _add_robot(self, request: SpawnRequest, pose: Pose, namespace: str) -> None:
        """A robot with its URDF's plugins (read and checked by parse_spawn, before anything
        is built; its meshes found then, each by the absolute path of its file)."""
        self.sim.add_robot(request.name, namespace, request.description, pose)

    @staticmethod
    def _pool_key(request: SpawnRequest) -> tuple:
        """The BodyPool key of a spawned model's bodies: its text's digest (a URDF's relative
        meshes are from the working directory)."""
        if request.description is not None:
            return ("urdf", request.digest, os.getcwd())
        return ("sdf", request.digest)

    def delete(self, name: str) -> None:
        check_names("DeleteModel: ", model_name=name)
        model = self._model(name, "DeleteModel")  # refuses an unknown name
        self.sim.forces.forget_model(name)   # its wrenches and efforts go with it
        key, built = self._spawned.pop(name, (None, []))
        bodies = list(dict.fromkeys(p.body.uid for p in model.parts))
        pool = self.sim.physics.body_pool
        # its bodies wait for the next spawn of the same text, unless they were rebuilt since
        if key is not None and bodies == built and pool.park(key, bodies):
            model.parts = []
        elif key is not None:   # (a robot's body is its RobotBody's to park)
            pool.forget(bodies + built)
        self.sim.remove_model(name)
