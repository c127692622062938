"""SDF: worlds, models, their frames, elements, inertia, lights, actors, saved state."""
