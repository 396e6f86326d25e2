"""Integer codes and array layouts shared by all kernels and the front end.

Everything a kernel exchanges with the front end is a flat array whose
entries are addressed by the constants below, the parameter vector of every
model included.  This module imports nothing (no Numba): the front end
builds kernel inputs without importing a kernel module.
"""

# ---- run status (returned by every entry kernel) ---------------------------
RUNNING = 0
SAFE_NO_UPLIFT = 1      # never left full contact
SAFE_REST = 2           # uplifted, came back to rest
SAFE_MOVING = 3         # upright but still moving at the end of the run
SAFE_BOUNDED = 4        # stopped early: free motion after the excitation
                        # provably cannot overturn (energy below the barrier)
OVERTURN_MODE1 = 5      # overturned after at least one impact
OVERTURN_MODE2 = 6      # overturned without any impact
LEANING = 7             # came to rest leaning on a wall (one-sided rocking)
FLIGHT = 8              # lost contact with the ground (G <= 0 or N = 0)
FAIL_STEP_UNDERFLOW = -1
FAIL_STEP_BUDGET = -2
FAIL_EVENT = -3         # event location failed (iteration cap)
FAIL_NONFINITE = -4     # NaN/inf in the state
FAIL_TRANSITIONS = -5   # too many discrete transitions without time advance
FAIL_OUTPUT_FULL = -6   # time-history buffer full (front end retries larger)
FAIL_INCONSISTENT = -7  # no contact mode is consistent (Painleve-type, friction)
FAIL_UNSTABLE = -8      # fixed step outside the integrator's stability region
FAIL_INTERRUPTED = -9   # stopped by the user (Ctrl-C) during the run
FAIL_FACE_CONTACT = -10  # guard: the base went into the wall (the face contact modes missed it)

# ---- discrete state vector (int64) -----------------------------------------
D_MODE = 0         # contact mode, model specific (MODE_* below)
D_PIVOT = 1        # active pivot s = +1 (right corner) / -1 (left)
D_STATIC = 2       # 1: state frozen, only the excitation can end the phase
D_WALL_REST = 3    # 1: resting against the wall
D_SLIP_DIR = 4     # slip direction sigma
D_AUX = 5
N_DISC = 8

# contact modes (shared names, models use the subset they need)
MODE_REST = 0
MODE_ROCK = 1
MODE_SLIDE = 2
MODE_SLIDE_ROCK = 3
MODE_FLIGHT = 4
MODE_OVERTURNED = 5
MODE_WALL_REST = 6

# ---- metrics vector (float64) ----------------------------------------------
M_MAX_ABS_THETA = 0    # rad
M_MAX_THETA_POS = 1    # rad, max of theta (>= 0)
M_MAX_THETA_NEG = 2    # rad, max of -theta (>= 0)
M_IMPACTS = 3          # ground impacts
M_WALL_IMPACTS = 4
M_T_UPLIFT = 5         # s, first uplift (nan: never)
M_T_OVER = 6           # s, overturning time (nan: none)
M_T_PASS_ALPHA = 7     # s, first time |theta| > alpha (nan: none)
M_NFEV = 8
M_NSTEPS = 9           # accepted steps
M_NREJECT = 10
M_T_FINAL = 11
M_T_LAST_IMPACT = 12
M_MAX_U = 13           # m, flexible deflection
M_MAX_SLIDE = 14       # m
M_RESIDUAL_SLIDE = 15  # m
M_T_SLIDE = 16         # s
M_T_SLIDE_ROCK = 17    # s
M_N_STICK_SLIP = 18
M_T_ROCK = 19          # s spent rocking
M_T_CONTACT = 20       # s spent in full contact
M_ENERGY_GAINS = 21    # impacts that created energy (I1 map)
M_N_EVENTS = 22
M_T_EXC_END = 23
M_T_PREV = 24         # s, time of the last bookkeeping (internal)
M_MIN_U = 25          # m, most negative deflection (internal)
M_T_UNLOADED = 26     # s spent with the pivot in tension (lift-off held)
M_N_LIFT_OFF = 27     # times N reached 0 while rocking (lift-off held)
M_T_SLIP_START = 28   # s, last slip start from stick (internal)
M_ERR_FIXED = 29      # fixed step: largest relative local error of a step
M_DT_STABLE = 30      # s, fixed step: a step that would be stable (failed runs)
N_MET = 32

# ---- solver options vector (float64) ---------------------------------------
O_RTOL = 0
O_ATOL = 1
O_DT_FIXED = 2      # > 0: fixed-step mode with this step
O_MAX_STEP = 3
O_MAX_STEPS = 4     # step budget (accepted + rejected)
O_T_END = 5
O_EARLY_EXIT = 6    # 1: stop once the outcome is decided
O_RECORD_BREAKS = 7  # 1: every record sample is a breakpoint
O_EPS_OMEGA = 8     # rad/s, chatter-to-rest velocity threshold
O_EPS_T = 9         # s, chatter-to-rest impact interval
O_T0 = 10
O_ABORT = 11        # set to 1 from outside (Ctrl-C): the run stops at once
O_METHOD = 12       # METHOD_*: integration method of the models with a stiff one
N_OPT = 13

# O_METHOD (kernels/rodas.py): explicit DP5 that turns to Rodas4 where the
# problem is stiff, DP5 only, or Rodas4 only
METHOD_AUTO = 0
METHOD_DOPRI = 1
METHOD_RODAS = 2

# ---- event log (float64 rows) ----------------------------------------------
LOG_T = 0
LOG_KIND = 1
LOG_PRE = 2     # velocity before
LOG_POST = 3    # velocity after
LOG_THETA = 4
LOG_PIVOT = 5
N_LOG = 6

EV_UPLIFT = 1
EV_IMPACT = 2
EV_WALL_IMPACT = 3
EV_OVERTURN = 4
EV_REST = 5
EV_PASS_ALPHA = 6
EV_WALL_REST = 7
EV_WALL_RELEASE = 8
EV_LEANING = 9
EV_FLIGHT = 10
EV_SLIP = 11
EV_STICK = 12
EV_PEAK = 13
EV_CONTACT = 14
EV_LIFT_OFF_HELD = 15   # N reached 0, pivot held down (friction, lift_off='hold')
EV_RELOAD = 16          # N > 0 again after a held lift-off

# ---- excitation header (float64), one block per channel ---------------------
X_KIND = 0
X_AMP = 1      # m/s^2 (sampled: scale factor applied to samples)
X_OMEGA = 2    # rad/s
X_SIGN = 3
X_T0 = 4       # s, start
X_DUR = 5      # s, duration (sampled: (n-1)*dt)
X_DT = 6       # s, sample spacing
X_OFFSET = 7   # first sample index in the shared sample array
X_N = 8        # number of samples
N_HDR = 9
H_CHANNEL = 0          # horizontal block starts here
V_CHANNEL = N_HDR      # vertical block starts here
# sloping ground: the kernels work in the slope's frame (x along the slope,
# positive downhill; z normal to it).  ground() turns the channels (a_h, a_v)
# into that frame: a_g' = a_h c_m - a_v s_m - g sin(phi),
# a_v' = a_v c_m + a_h s_m + (g cos(phi) - g), so G' = g + a_v' is the normal
# component of gravity less the ground's acceleration.  (c_m, s_m) =
# (cos phi, sin phi) for channels given horizontal/vertical, (1, 0) for
# channels given along/normal to the slope.  S_ON = 0: level ground, and
# ground() returns the channels untouched.
S_BLOCK = 2 * N_HDR
S_ON = S_BLOCK
S_CM = S_BLOCK + 1
S_SM = S_BLOCK + 2
S_G_T = S_BLOCK + 3     # m/s^2, g sin(phi)
S_G_N = S_BLOCK + 4     # m/s^2, g cos(phi) - g (= -2 g sin^2(phi/2))
N_EXC = 2 * N_HDR + 5

EXC_NONE = 0
EXC_ONE_SINE = 1
EXC_HALF_SINE = 2
EXC_ONE_COSINE = 3
EXC_SAMPLED = 4
EXC_RECTANGULAR = 5

# ---- parameter vectors (float64), one layout per model ---------------------
# Every model starts with the rigid entries: the shared kernel pieces
# (rigid.overturned, passed_alpha, ...) read alpha, p, e, g, theta_over there.
P_ALPHA = 0
P_P = 1
P_E = 2
P_G = 3
P_THETA_OVER = 4
# rear wall (kernels.wall)
P_WALL_SIDE = 5     # w = +1 / -1
P_THETA_W = 6       # rad, limit angle
P_E_W = 7           # wall restitution
P_HOGAN = 8         # 1: gap d = 0, Hogan's one-sided map
N_PAR_RIGID = 10
# asymmetric rigid body (kernels.rigid, the rigid_body entries): the rigid
# entries above hold the side of pivot s = +1 (the right base corner, at
# (b2, -h2) from the centre of mass: alpha_2, p_2, and P_E the restitution of
# an impact from pivot +1 onto pivot -1); these hold the side of pivot -1
P_ALPHA_NEG = 10    # rad, alpha_1 = atan(b1/h1)
P_P_NEG = 11        # rad/s, p_1
P_E_NEG = 12        # restitution of an impact from pivot -1 onto pivot +1
P_IO_RATIO = 13     # I_O,1 / I_O,2: inertia about pivot -1 over that about +1
N_PAR_RIGID_BODY = 14
# rigid block or asymmetric body against a rear wall (kernels.wall): the
# rigid_body vector (both sides; a symmetric block fills P_*_NEG with its own
# alpha, p, e and P_IO_RATIO with 1) with the wall entries P_WALL_SIDE ...
# P_HOGAN above
N_PAR_WALL = N_PAR_RIGID_BODY

# rigid block with friction (kernels.friction), after the rigid entries
Q_B = 10            # m, half-width
Q_H = 11            # m, half-height (CM height above the base)
Q_IG = 12           # m^2, I_G / M
Q_MU_S = 13
Q_MU_K = 14
N_PAR_FRICTION = 16

# flexible body (kernels.flexible); the first five entries are the rigid ones
F_ALPHA = 0
F_P = 1
F_E = 2             # restitution factor on theta'+ (I1 map only)
F_G = 3
F_THETA_OVER = 4
F_B = 5             # m, base half-width
F_H = 6             # m, mass height
F_WN = 7            # rad/s, omega_n = sqrt(K/m)
F_ZETA = 8
F_IM = 9            # m^2, I_m / m
F_IMPACT = 10       # IMPACT_FULL_CONTACT (I3) or IMPACT_PIVOT_SWITCH (I1)
F_MB = 11           # m_b / m, rigid base mass (0: the classic massless base)
F_IB = 12           # m^2, I_b / m, base inertia about its own CM
F_HB = 13           # m, base CM height h_b
N_PAR_FLEXIBLE = 14
IMPACT_FULL_CONTACT = 0
IMPACT_PIVOT_SWITCH = 1

# flexible body with friction (kernels.flexible_friction), after the flexible entries
F_MU_S = 14
F_MU_K = 15
F_LIFT_OFF = 16     # LIFT_OFF_STOP: stop with FLIGHT when N reaches 0 while
#                     rocking; LIFT_OFF_HOLD: hold the pivot down (bilateral,
#                     as the classic models do) with no friction while N < 0
N_PAR_FLEXIBLE_FRICTION = 18

# flexible body against a rear wall (kernels.flexible_wall), after the flexible entries
FW_WALL_SIDE = 14   # w = +1 / -1
FW_THETA_W = 15     # rad, limit angle of the body's outline (the 2B x 2H box)
FW_E_W = 16         # wall restitution
N_PAR_FLEXIBLE_WALL = 18
LIFT_OFF_STOP = 0
LIFT_OFF_HOLD = 1

# block on a flexible foundation (kernels.foundation), after the rigid entries;
# SI units (kg, m, N/m, N s/m, N m/rad, N m s/rad)
P_MASS = 10         # kg
P_I_G = 11          # kg m^2, centroidal inertia
P_B = 12            # m, half-width (corner at x = +-b)
P_H = 13            # m, height of the centre of mass above the base
P_KV = 14           # N/m, corner spring (two_spring)
P_CV = 15           # N s/m, corner dashpot (two_spring)
P_KT = 16           # N m/rad, rotational spring (switching, linear)
P_CT = 17           # N m s/rad, rotational dashpot
P_EF = 18           # -, restitution at re-contact (switching)
P_THETA_Y = 19      # rad, M g b / k_t (switching)
P_I_C = 20          # kg m^2, I_G + M h^2 (inertia about the base centre)
P_I_0 = 21          # kg m^2, I_G + M R^2 (inertia about a corner)
P_B_SKEW = 22       # m, c = (b2 - b1)/2: base centre right of the point below the CM (0: symmetric)
P_ALPHA_LEFT = 23   # rad, alpha of the left corner's side (theta < 0; P_ALPHA if symmetric)
N_PAR_FOUNDATION = 24

# flexible body on the two-spring foundation (kernels.foundation_flexible): the
# two-spring vector of the body with its column locked (P_MASS = m + m_b, P_H
# and P_I_G of the locked body, P_B = B), then the column and the base, SI
PF_M = 24           # kg, the column's mass m
PF_H = 25           # m, its height H above the base
PF_WN = 26          # rad/s, omega_n = sqrt(K/m)
PF_ZETA = 27        # -, column damping ratio
PF_IM = 28          # kg m^2, I_m (rotates with the base)
PF_MB = 29          # kg, base mass m_b (> 0)
PF_IB = 30          # kg m^2, base inertia about its own centre of mass
PF_HB = 31          # m, base CM height h_b
N_PAR_FOUNDATION_FLEXIBLE = 32

# planar rigid body with contact points (kernels.contact), after the rigid
# entries (P_WALL_SIDE and P_E_W as the wall model); the first five share the
# friction model's indices, so a friction vector padded with C_B2 = Q_B,
# C_H2 = Q_H, C_E_NEG = P_E and C_ALPHA_NEG = P_ALPHA is a contact vector;
# as in the rigid_body entries, P_ALPHA and P_E belong to the right pivot
# (+1: its alpha, the impact leaving it) and the *_NEG entries to the left
C_B1 = 10           # m, half-width left of the centre of mass
C_H1 = 11           # m, CM height above the left base corner
C_IG = 12           # m^2, I_G / M
C_MU_S = 13         # static friction at the base (inf: never slips)
C_MU_K = 14
C_B2 = 15           # m, half-width right of the CM
C_H2 = 16           # m, CM height above the right base corner
C_GAP = 17          # m, clear wall gap d (inf: no wall)
C_MU_W = 18         # wall friction mu_w (0: frictionless)
C_HT1 = 19          # m, height of the top-left corner above the CM
C_HT2 = 20          # m, height of the top-right corner above the CM
C_E_NEG = 21        # ground restitution of an impact from pivot -1 onto +1
C_ALPHA_NEG = 22    # rad, alpha of the left pivot (-1)
C_H_WALL = 23       # m, height of a wall lower than the wall-side top corner (0: a tall wall)
C_TOP_R = 24        # m, radius rho of a rounded wall-side top corner (0: the square corner)
N_PAR_CONTACT = 25
LIFT_OFF_FLIGHT = 2   # Friction(lift_off="flight"): the contact model flies

# metrics of free flight, in slots the other rigid models leave free
M_N_FLIGHTS = M_N_LIFT_OFF      # number of flights
M_T_FLIGHT = M_T_UNLOADED       # s in flight
M_MAX_JUMP = 31                 # m, largest rise of the CM above its rest height in a flight
# flexible body against a wall: pivot-switch wall impacts replaced by the
# energy-safe map (kernels.flexible_wall)
M_WALL_CAPPED = 31
# flexible body with friction and free flight (kernels.flexible_flight): the
# flexible-friction vector with F_LIFT_OFF = LIFT_OFF_FLIGHT (mu_s may be inf)
N_PAR_FLEXIBLE_FLIGHT = N_PAR_FLEXIBLE_FRICTION

#: Small-gap limit of the wall models: a wall closer than this rotation [rad]
#: is taken at theta = 0 (kernels/wall.py and kernels/flexible_wall.py)
SMALL_GAP_ANGLE = 1e-7
