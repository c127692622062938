"""gazebo_ros's ``Physics.cfg`` as the module dynamic_reconfigure's generator makes of it
(``PhysicsConfig.py``), written out here so that no build step is needed: the parameters,
types, defaults and limits of ``gazebo_ros/cfg/Physics.cfg`` (doc/turtlebot3.md 2.6),
all at level 1, in the form ``dynamic_reconfigure.server.Server`` reads.
"""
from dynamic_reconfigure.encoding import extract_params

inf = float('inf')

# name, type, default, min, max, description
_PARAMETERS = (
    ("time_step", "double", 0.001, 0.0, 10.0, "Time step (s) of one physics update"),
    ("max_update_rate", "double", 60.0, 0.0, 1000.0,
     "Physics updates per wall second aimed at; 0 = as fast as possible, else at least "
     "0.01 / time_step (a real-time factor of 0.01: lower is refused)"),
    ("gravity_x", "double", 0.0, -100.0, 100.0, "Gravity along x (m/s^2)"),
    ("gravity_y", "double", 0.0, -100.0, 100.0, "Gravity along y (m/s^2)"),
    ("gravity_z", "double", -9.8, -100.0, 100.0, "Gravity along z (m/s^2)"),
    ("auto_disable_bodies", "bool", False, False, True, "Disable bodies at rest (ODE)"),
    ("sor_pgs_precon_iters", "int", 0, 0, 10000, "Preconditioning iterations (ODE)"),
    ("sor_pgs_iters", "int", 20, 0, 10000, "Solver iterations (Bullet: numSolverIterations)"),
    ("sor_pgs_w", "double", 1.3, 0.0, 5.0, "Successive over-relaxation factor (ODE)"),
    ("sor_pgs_rms_error_tol", "double", -1.0, -1.0, 10000.0, "RMS error tolerance (ODE)"),
    ("cfm", "double", 0.0, 0.0, 10.0, "Constraint force mixing (Bullet: globalCFM)"),
    ("erp", "double", 0.2, 0.0, 10.0, "Error reduction parameter (Bullet: erp, contactERP)"),
    ("contact_surface_layer", "double", 0.001, 0.0, 10.0, "Contact surface layer (ODE)"),
    ("contact_max_correcting_vel", "double", 100.0, 0.0, 10000000.0,
     "Maximum contact correcting velocity (ODE)"),
    ("max_contacts", "int", 100, 0, 10000000, "Maximum contacts per collision pair (ODE)"),
)

config_description = {
    'name': 'Default', 'type': '', 'state': True, 'cstate': 'true', 'id': 0, 'parent': 0,
    'parameters': [
        {'name': name, 'type': kind, 'default': default, 'level': 1, 'description': text,
         'min': low, 'max': high, 'srcline': 0, 'srcfile': 'Physics.cfg', 'edit_method': '',
         'ctype': 'std::string' if kind == 'str' else kind,
         'cconsttype': 'const ' + ('char * const' if kind == 'str' else kind)}
        for name, kind, default, low, high, text in _PARAMETERS],
    'groups': [], 'srcline': 0, 'srcfile': 'Physics.cfg', 'class': 'DEFAULT',
    'parentclass': '', 'parentname': 'Default', 'field': 'default', 'upper': 'DEFAULT',
    'lower': 'groups'}

min = {}
max = {}
defaults = {}
level = {}
type = {}
all_level = 0

for param in extract_params(config_description):
    min[param['name']] = param['min']
    max[param['name']] = param['max']
    defaults[param['name']] = param['default']
    level[param['name']] = param['level']
    type[param['name']] = param['type']
    all_level = all_level | param['level']
