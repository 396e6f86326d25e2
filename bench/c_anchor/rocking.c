/*
 * rocking.c -- a plain C anchor for fastrock's speed (issue #15, item 1).
 *
 * An event-driven Dormand-Prince 5(4) solver (the RK45 of SciPy: same
 * tableau, same embedded error estimator, RMS error norm, safety 0.9, step
 * factors limited to [0.2, 10], SciPy's initial step selection, the 4th-order
 * dense output) for
 *
 *   (a) the rigid Housner block, two-sided rocking (fastrock kernels/rigid.py),
 *   (b) the same block beside a rigid rear wall (kernels/wall.py),
 *
 * under a one-sine ground pulse a_g = sign a_p sin(omega t) on [0, T],
 * T = 2 pi / omega (zero outside; the pulse end is a breakpoint that no step
 * straddles).  Written from scratch for this benchmark, in plain C99 with no
 * dependency but libm; one function, ``rock_grid``, runs a whole grid.
 *
 * Physics (units: rad, rad/s, m/s^2):
 *   rocking about pivot s (+1 right corner, -1 left), G = g (no vertical
 *   ground motion):
 *       theta'' = -p^2 [ sin(s alpha - theta) + (a_g/g) cos(s alpha - theta) ]
 *   uplift from rest when |a_g| > g tan(alpha) (1 + 1e-14), with s = -sgn(a_g);
 *   ground impact at theta = 0 (s theta reaches 0 from above):
 *       theta'+ = e theta'-, s -> -s   (Housner);
 *   chatter-to-rest: |theta'+| < eps_omega, or two impacts closer than eps_t:
 *       theta' = 0, then the uplift test decides rocking or rest;
 *   overturning at s theta = theta_over: mode 1 after an impact, else mode 2.
 * Wall on side w (+1/-1), limit angle theta_w (inf: never reached):
 *   while s == w the wall is hit at w theta = theta_w: theta'+ = -e_w theta'-,
 *   pivot kept; chatter at the wall settles the block on it (static phase
 *   while w theta'' at rest on the wall is >= 0, released when it turns
 *   negative; after the pulse the margin uses the zero right limit);
 *   gap 0 (hogan != 0): Hogan's map at theta = 0, theta'+ = -e_w theta'-,
 *   pivot kept on the far corner, uplift from rest away from the wall only.
 *   Leaning: at rest on the wall at the end with theta_w > alpha, or after the
 *   pulse on the near corner past alpha with energy below 1 - cos(alpha).
 *
 * Early decisions (early != 0), once the pulse is over and the block rocks:
 *   two-sided: energy E = theta'^2/(2 p^2) + cos(alpha - s theta) - cos(alpha)
 *     below the barrier 1 - cos(alpha) with s theta < alpha: safe (bounded),
 *     the next two peaks in closed form; moving outward past the barrier:
 *     overturns (the fall time, an elliptic integral, must end before t_end);
 *   wall: the safe rule with the toward-wall peak capped at theta_w and the
 *     energy the wall impact takes folded into the next peak; trapped on the
 *     wall past alpha: leaning.  (No early overturning decision, as fastrock.)
 *
 * Output codes (the same numbers as fastrock's kernels/layout.py):
 *   1 safe:no-uplift  2 safe:rest  3 safe:moving  4 safe:bounded
 *   5 overturn mode 1  6 overturn mode 2  7 leaning
 *   -1 step underflow  -2 step budget  -3 event location  -5 transition loop
 *
 * Work counters: nfev counts right-hand-side evaluations as SciPy counts them
 * (6 per step attempt, 1 per phase start, 1 per initial step selection, 1 at
 * the pulse end); nsteps counts accepted steps.  Event functions (and the
 * peak observer, which evaluates theta'') are not counted, as in SciPy.
 */
#include <math.h>
#include <stdint.h>

/* ---- status codes ------------------------------------------------------ */
enum {
    RUNNING = 0, SAFE_NO_UPLIFT = 1, SAFE_REST = 2, SAFE_MOVING = 3,
    SAFE_BOUNDED = 4, OVERTURN_MODE1 = 5, OVERTURN_MODE2 = 6, LEANING = 7,
    FAIL_STEP_UNDERFLOW = -1, FAIL_STEP_BUDGET = -2, FAIL_EVENT = -3,
    FAIL_TRANSITIONS = -5
};

enum { MODE_REST = 0, MODE_ROCK = 1, MODE_WALL_REST = 6 };

/* Events: ground impact, overturning, the peak observer (max |theta|), the
 * pass-alpha observer (first time |theta| reaches alpha), and the wall (last,
 * wall model only).  fastrock's kernels evaluate these too (plus a flight
 * event, inactive without vertical ground motion).  -DNO_PASS_ALPHA drops the
 * pass-alpha observer, which no outcome needs: its grazing test fires at every
 * rocking peak (see bracket_kind), so it is not free. */
#ifdef NO_PASS_ALPHA
enum { EV_IMPACT, EV_OVERTURN, EV_PEAK, EV_WALL, N_EV_MAX, EV_PASS = -1 };
static const int TERMINAL[N_EV_MAX] = {1, 1, 0, 1};
#else
enum { EV_IMPACT, EV_OVERTURN, EV_PEAK, EV_PASS, EV_WALL, N_EV_MAX };
static const int TERMINAL[N_EV_MAX] = {1, 1, 0, 0, 1};
#endif

/* bracket kinds of an event on one step */
enum { NO_ROOT = 0, SIGN_CHANGE = 1, SEARCH_MIN = 2, SEARCH_MAX = 3, AT_START = 4 };

#define MAX_BISECT 200
#define MAX_FALSI (4 * MAX_BISECT)
#define MAX_ZERO_LENGTH 200
#define UPLIFT_RTOL 1e-14
#define EPS_MACH 2.220446049250313e-16
#define PI 3.141592653589793

/* ---- Dormand-Prince 5(4) ----------------------------------------------- */
static const double SAFETY = 0.9, MIN_FACTOR = 0.2, MAX_FACTOR = 10.0;
#define ERR_EXP (-1.0 / 5.0)

static const double C2 = 1.0 / 5, C3 = 3.0 / 10, C4 = 4.0 / 5, C5 = 8.0 / 9;
static const double A21 = 1.0 / 5;
static const double A31 = 3.0 / 40, A32 = 9.0 / 40;
static const double A41 = 44.0 / 45, A42 = -56.0 / 15, A43 = 32.0 / 9;
static const double A51 = 19372.0 / 6561, A52 = -25360.0 / 2187,
                    A53 = 64448.0 / 6561, A54 = -212.0 / 729;
static const double A61 = 9017.0 / 3168, A62 = -355.0 / 33,
                    A63 = 46732.0 / 5247, A64 = 49.0 / 176,
                    A65 = -5103.0 / 18656;
static const double B1 = 35.0 / 384, B3 = 500.0 / 1113, B4 = 125.0 / 192,
                    B5 = -2187.0 / 6784, B6 = 11.0 / 84;
/* error estimator: y5 - y4 = h sum E_j k_j */
static const double E1 = -71.0 / 57600, E3 = 71.0 / 16695, E4 = -71.0 / 1920,
                    E5 = 17253.0 / 339200, E6 = -22.0 / 525, E7 = 1.0 / 40;
/* dense output: y(t_old + x h) = y_old + h sum_k Q_k x^(k+1), Q = K^T P */
static const double PD[7][4] = {
    {1.0, -8048581381.0 / 2820520608, 8663915743.0 / 2820520608,
     -12715105075.0 / 11282082432},
    {0.0, 0.0, 0.0, 0.0},
    {0.0, 131558114200.0 / 32700410799, -68118460800.0 / 10900136933,
     87487479700.0 / 32700410799},
    {0.0, -1754552775.0 / 470086768, 14199869525.0 / 1410260304,
     -10690763975.0 / 1880347072},
    {0.0, 127303824393.0 / 49829197408, -318862633887.0 / 49829197408,
     701980252875.0 / 199316789632},
    {0.0, -282668133.0 / 205662961, 2019193451.0 / 616988883,
     -1453857185.0 / 822651844},
    {0.0, 40617522.0 / 29380423, -110615467.0 / 29380423,
     69997945.0 / 29380423}};

/* ---- one case ------------------------------------------------------------ */
typedef struct {
    /* block */
    double alpha, p, e, g, theta_over, tan_alpha;
    /* wall */
    int wall, hogan;
    double wside, theta_w, e_w;
    /* pulse: a_g = amp sin(omega t) on [0, dur] (amp carries the sign) */
    double amp, omega, dur;
    /* solver */
    double rtol, atol, t_end, eps_omega, eps_t;
    int early;
    double max_steps;
} Case;

typedef struct {
    int mode, pivot, stat;
} Disc;

typedef struct {
    double max_abs, impacts, wall_impacts, t_uplift, t_last_impact, t_final;
    double t_pass_alpha;
    double nfev, nsteps;
} Met;

/* spacing of doubles at |t| (t >= 0 in practice) */
static double ulp(double t)
{
    double a = fabs(t);
    int ex;
    if (a == 0.0)
        return 5e-324;
    frexp(a, &ex);
    return ldexp(1.0, ex - 53);
}

static inline double next_up(double t) { return t + ulp(t); }

static inline double ground(const Case *c, double t)
{
    if (t < 0.0 || t > c->dur)
        return 0.0;
    return c->amp * sin(c->omega * t);
}

static inline double next_breakpoint(const Case *c, double t)
{
    if (t < 0.0)
        return 0.0;
    if (t >= c->dur)
        return INFINITY;
    return c->dur;
}

/* Housner's equation of motion about pivot s (G = g) */
static inline double housner(const Case *c, double theta, int s, double ag)
{
    double phi = s * c->alpha - theta;
    double p = c->p;
    return -p * p * (c->g * sin(phi) + ag * cos(phi)) / c->g;
}

static inline void rhs(const Case *c, int s, double t, const double *y,
                       double *f)
{
    f[0] = y[1];
    f[1] = housner(c, y[0], s, ground(c, t));
}

/* event k at (t, y): value g (> 0 admissible) and dg/dt */
static inline void event(const Case *c, const Disc *d, int k, double t,
                         const double *y, double *g, double *gd)
{
    int s = d->pivot;
    switch (k) {
    case EV_IMPACT:
        *g = s * y[0];
        *gd = s * y[1];
        return;
    case EV_OVERTURN:
        *g = c->theta_over - s * y[0];
        *gd = -s * y[1];
        return;
    case EV_PEAK:
        *g = s * y[1];
        *gd = s * housner(c, y[0], s, ground(c, t));
        return;
#ifndef NO_PASS_ALPHA
    case EV_PASS:
        *g = c->alpha - s * y[0];
        *gd = -s * y[1];
        return;
#endif
    default: /* EV_WALL */
        if (s == c->wside) {
            *g = c->theta_w - c->wside * y[0];
            *gd = -c->wside * y[1];
        } else {
            *g = INFINITY;
            *gd = 0.0;
        }
        return;
    }
}

/* ---- metrics and closed forms --------------------------------------------- */
static inline void track(Met *m, double theta)
{
    double a = fabs(theta);
    if (a > m->max_abs)
        m->max_abs = a;
}

static double peak_from_energy(double alpha, double energy)
{
    double cc = cos(alpha) + energy;
    if (cc >= 1.0)
        return alpha;
    return alpha - acos(cc);
}

static inline double free_energy(const Case *c, const double *y, int s)
{
    return 0.5 * y[1] * y[1] / (c->p * c->p) + cos(c->alpha - s * y[0]) -
           cos(c->alpha);
}

/* Carlson's R_F (duplication, 5th-order series, ERRTOL 0.0025) */
static double carlson_rf(double x, double y, double z)
{
    double mu = 1.0, dx = 0.0, dy = 0.0, dz = 0.0;
    for (int i = 0; i < 64; i++) {
        mu = (x + y + z) / 3.0;
        dx = 1.0 - x / mu;
        dy = 1.0 - y / mu;
        dz = 1.0 - z / mu;
        if (fmax(fabs(dx), fmax(fabs(dy), fabs(dz))) < 0.0025)
            break;
        double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
        double lam = sx * (sy + sz) + sy * sz;
        x = 0.25 * (x + lam);
        y = 0.25 * (y + lam);
        z = 0.25 * (z + lam);
    }
    double e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
    return (1.0 + (e2 / 24.0 - 0.1 - 3.0 * e3 / 44.0) * e2 + e3 / 14.0) /
           sqrt(mu);
}

/* antiderivative of 1/sqrt(c + sin^2 phi), zero at phi = 0 or at pi/2 */
static double fall_integral(double phi, double cc, int beyond)
{
    if (!beyond) {
        double sp = sin(phi), cp = cos(phi);
        return sp * carlson_rf(cc * cp * cp, cc + sp * sp, cc);
    }
    double sq = cos(phi), cq = sin(phi);
    return -sq * carlson_rf((1.0 + cc) * cq * cq, cc + cq * cq, 1.0 + cc);
}

/* Two-sided block after the pulse, rocking outward past the barrier: the
 * time to reach theta_over (free rocking, no impact on the way), or NaN;
 * *dt_alpha: the time to reach alpha (NaN if past it already). */
static double fall_time(const Case *c, double theta, double w, int s,
                        double *dt_alpha)
{
    *dt_alpha = NAN;
    if (!(s * w > 0.0))
        return NAN;
    double u0 = s * theta - c->alpha;
    if (!(u0 < c->theta_over - c->alpha))
        return NAN;
    double q = 0.5 * w / c->p, phi0 = 0.5 * u0, sh = sin(phi0);
    double cc = q * q - sh * sh;
    int beyond = phi0 >= 0.0;
    if (!(beyond || cc > 0.0))
        return NAN;
    double f0 = fall_integral(phi0, cc, beyond);
    double f1 = fall_integral(0.5 * (c->theta_over - c->alpha), cc, beyond);
    if (!beyond)
        *dt_alpha = -f0 / c->p; /* the integral is 0 at alpha */
    return (f1 - f0) / c->p;
}

/* wall: next two peaks of free rocking with energy below the barrier */
static void fold_peaks(const Case *c, const double *y, int s, Met *m)
{
    double a = c->alpha, w = c->wside, tw = c->theta_w;
    double ew2 = c->e_w * c->e_w;
    double e2 = c->hogan ? ew2 : c->e * c->e;
    double E = free_energy(c, y, s);
    int side;
    if (s * y[1] > 0.0) {
        side = s;
    } else {
        side = c->hogan ? s : -s;
        E *= e2;
    }
    for (int i = 0; i < 2; i++) {
        double pk = peak_from_energy(a, E);
        if (side == w && pk >= tw) {
            pk = tw;
            double pe = cos(a - tw) - cos(a);
            E = pe + ew2 * (E - pe);
        }
        track(m, side * pk);
        E *= e2;
        if (!c->hogan)
            side = -side;
    }
}

static int trapped_on_wall(const Case *c, const double *y, const Disc *d)
{
    if (d->pivot != c->wside || !(c->theta_w < c->theta_over))
        return 0;
    double a = c->alpha;
    return c->wside * y[0] > a && free_energy(c, y, d->pivot) < 1.0 - cos(a);
}

/* ---- static phases ---------------------------------------------------------- */
/* w theta'' at rest on the wall (>= 0: pressed on it); zero excitation from
 * the end of the pulse on */
static double wall_rest_margin(const Case *c, double t)
{
    double ag = t >= c->dur ? 0.0 : ground(c, t);
    double m = c->wside * housner(c, c->wside * c->theta_w, (int)c->wside, ag);
    return fmin(m, c->g);
}

static double static_margin(const Case *c, const Disc *d, double t)
{
    double ag = ground(c, t);
    if (c->wall) {
        if (d->mode == MODE_WALL_REST)
            return wall_rest_margin(c, t);
        if (c->hogan)
            return fmin(c->g * c->tan_alpha * (1.0 + UPLIFT_RTOL) -
                            c->wside * ag, c->g);
    }
    return c->g * c->tan_alpha * (1.0 + UPLIFT_RTOL) - fabs(ag);
}

/* next trial point inside (lo, hi): secant, or midpoint */
static inline double falsi_point(double lo, double hi, double glo, double ghi,
                                 double tol, int bisect)
{
    if (!bisect) {
        double m = hi - ghi * (hi - lo) / (ghi - glo);
        m = fmin(fmax(m, lo + 0.5 * tol), hi - 0.5 * tol);
        if (lo < m && m < hi)
            return m;
    }
    return 0.5 * (lo + hi);
}

/* First time in [t, t_stop] where the static margin turns negative (inf if
 * none): scan a grid of T/64 (pulse extrema lie on it), then Illinois regula
 * falsi in the first interval that ends below zero. */
static double static_exit(const Case *c, const Disc *d, double t,
                          double t_stop)
{
    double g = static_margin(c, d, t);
    if (g < 0.0)
        return t;
    double hs = c->dur / 64.0;
    if (!isfinite(hs) || hs <= 0.0)
        return INFINITY;
    double j = fmax(floor(t / hs) + 1.0, 0.0);
    double lo = t, glo = g;
    for (;;) {
        double tk = j * hs;
        if (tk <= lo) {
            j += 1.0;
            continue;
        }
        if (tk > t_stop)
            tk = t_stop;
        g = static_margin(c, d, tk);
        if (g < 0.0) {
            double hi = tk, ghi = g;
            int side = 0;
            for (int it = 0; it < MAX_FALSI; it++) {
                double tol = 4.0 * EPS_MACH * fmax(fabs(hi), 1.0);
                if (hi - lo <= tol)
                    break;
                double m = falsi_point(lo, hi, glo, ghi, tol, it % 4 == 3);
                double gm = static_margin(c, d, m);
                if (gm >= 0.0) {
                    if (side == 1)
                        ghi *= 0.5;
                    lo = m;
                    glo = gm;
                    side = 1;
                } else {
                    if (side == -1)
                        glo *= 0.5;
                    hi = m;
                    ghi = gm;
                    side = -1;
                }
            }
            return hi;
        }
        if (tk >= t_stop)
            return INFINITY;
        lo = tk;
        glo = g;
        j += 1.0;
    }
}

/* ---- transitions -------------------------------------------------------------- */
/* from theta = theta' = 0: uplift test, else rest */
static void start_rocking_or_rest(const Case *c, Disc *d, Met *m, double t)
{
    double ag = ground(c, t);
    double thr = c->g * c->tan_alpha * (1.0 + UPLIFT_RTOL);
    if (c->wall && c->hogan) {
        if (c->wside * ag <= thr) {
            d->mode = MODE_REST;
            d->stat = 1;
            return;
        }
    }
    if (fabs(ag) > thr) {
        d->mode = MODE_ROCK;
        d->stat = 0;
        d->pivot = ag > 0.0 ? -1 : 1;
        if (isnan(m->t_uplift))
            m->t_uplift = t;
    } else {
        d->mode = MODE_REST;
        d->stat = 1;
    }
}

static int is_chatter(const Case *c, Met *m, double t, double post)
{
    int ch = fabs(post) < c->eps_omega || t - m->t_last_impact < c->eps_t;
    m->t_last_impact = t;
    return ch;
}

static int overturned(Met *m, double theta)
{
    track(m, theta);
    return m->impacts > 0 ? OVERTURN_MODE1 : OVERTURN_MODE2;
}

/* terminal event k at time t, state y (updated in place) */
static int transition(const Case *c, Disc *d, Met *m, int k, double t,
                      double *y)
{
    if (k < 0) { /* end of a static phase */
        if (d->mode == MODE_WALL_REST) {
            d->mode = MODE_ROCK;
            d->stat = 0;
            d->pivot = c->wside > 0.0 ? 1 : -1;
            y[0] = c->wside * c->theta_w;
            y[1] = 0.0;
            return RUNNING;
        }
        start_rocking_or_rest(c, d, m, t);
        return RUNNING;
    }
    if (k == EV_IMPACT) {
        double pre = y[1];
        if (c->wall && c->hogan) { /* ground + wall impact, pivot kept */
            double post = -c->e_w * pre;
            y[0] = 0.0;
            y[1] = post;
            m->impacts += 1;
            m->wall_impacts += 1;
            if (is_chatter(c, m, t, post)) {
                y[1] = 0.0;
                start_rocking_or_rest(c, d, m, t);
            }
            return RUNNING;
        }
        double post = c->e * pre;
        y[0] = 0.0;
        y[1] = post;
        d->pivot = -d->pivot;
        m->impacts += 1;
        if (is_chatter(c, m, t, post)) {
            y[1] = 0.0;
            start_rocking_or_rest(c, d, m, t);
        }
        return RUNNING;
    }
    if (k == EV_OVERTURN)
        return overturned(m, y[0]);
    /* EV_WALL */
    double pre = y[1];
    double post = -c->e_w * pre;
    y[0] = c->wside * c->theta_w;
    y[1] = post;
    m->wall_impacts += 1;
    track(m, y[0]);
    if (is_chatter(c, m, t, post)) { /* settle on the wall if pressed on it */
        y[0] = c->wside * c->theta_w;
        y[1] = 0.0;
        if (wall_rest_margin(c, t) >= 0.0) {
            d->mode = MODE_WALL_REST;
            d->stat = 1;
        }
    }
    return RUNNING;
}

static int final_status(const Disc *d, const Met *m)
{
    if (d->mode == MODE_REST)
        return isnan(m->t_uplift) ? SAFE_NO_UPLIFT : SAFE_REST;
    return SAFE_MOVING;
}

/* after an accepted step: metrics, early decisions, final status */
static int after_step(const Case *c, Disc *d, Met *m, double t, double *y,
                      int at_end)
{
    double theta = y[0], w = y[1];
    int s = d->pivot;
    double a = c->alpha;
    track(m, theta);
    if (!c->wall) {
        if (at_end)
            return final_status(d, m);
        if (!c->early || d->mode != MODE_ROCK || t < c->dur)
            return RUNNING;
        if (s * theta < a) {
            double E = 0.5 * w * w / (c->p * c->p) + cos(a - s * theta) - cos(a);
            if (E < 1.0 - cos(a)) {
                double e2 = c->e * c->e, e1;
                int side1;
                if (s * w > 0.0) {
                    side1 = s;
                    e1 = E;
                } else {
                    side1 = -s;
                    e1 = e2 * E;
                }
                track(m, side1 * peak_from_energy(a, e1));
                track(m, -side1 * peak_from_energy(a, e2 * e1));
                return SAFE_BOUNDED;
            }
        }
        double dt_alpha, dt_over = fall_time(c, theta, w, s, &dt_alpha);
        if (!isnan(dt_over) && t + dt_over <= c->t_end) {
            /* completes the fall in closed form */
            m->t_final = t + dt_over;
            if (isfinite(dt_alpha) && isnan(m->t_pass_alpha))
                m->t_pass_alpha = t + dt_alpha;
            track(m, c->theta_over);
            return m->impacts > 0 ? OVERTURN_MODE1 : OVERTURN_MODE2;
        }
        return RUNNING;
    }
    if (at_end) {
        if (d->mode == MODE_WALL_REST)
            return c->theta_w > a ? LEANING : SAFE_REST;
        if (d->mode != MODE_REST && t >= c->dur && trapped_on_wall(c, y, d)) {
            track(m, c->wside * c->theta_w);
            return LEANING;
        }
        return final_status(d, m);
    }
    if (c->early && d->mode == MODE_ROCK && t >= c->dur &&
        free_energy(c, y, s) < 1.0 - cos(a)) {
        if (s * theta < a) {
            fold_peaks(c, y, s, m);
            return SAFE_BOUNDED;
        }
        if (trapped_on_wall(c, y, d)) {
            track(m, c->wside * c->theta_w);
            return LEANING;
        }
    }
    return RUNNING;
}

/* ---- integrator pieces ------------------------------------------------------------ */
/* one DP5 step from (t, y) with f = f(t, y): K[0..6], y_new; 6 rhs calls */
static inline void rk_step(const Case *c, int s, double t, const double *y,
                           const double *f, double h, double K[7][2],
                           double *y_new)
{
    double yt[2];
    K[0][0] = f[0];
    K[0][1] = f[1];
    for (int i = 0; i < 2; i++)
        yt[i] = y[i] + (K[0][i] * A21) * h;
    rhs(c, s, t + C2 * h, yt, K[1]);
    for (int i = 0; i < 2; i++)
        yt[i] = y[i] + (K[0][i] * A31 + K[1][i] * A32) * h;
    rhs(c, s, t + C3 * h, yt, K[2]);
    for (int i = 0; i < 2; i++)
        yt[i] = y[i] + (K[0][i] * A41 + K[1][i] * A42 + K[2][i] * A43) * h;
    rhs(c, s, t + C4 * h, yt, K[3]);
    for (int i = 0; i < 2; i++)
        yt[i] = y[i] + (K[0][i] * A51 + K[1][i] * A52 + K[2][i] * A53 +
                        K[3][i] * A54) * h;
    rhs(c, s, t + C5 * h, yt, K[4]);
    for (int i = 0; i < 2; i++)
        yt[i] = y[i] + (K[0][i] * A61 + K[1][i] * A62 + K[2][i] * A63 +
                        K[3][i] * A64 + K[4][i] * A65) * h;
    rhs(c, s, t + h, yt, K[5]);
    for (int i = 0; i < 2; i++)
        y_new[i] = y[i] + h * (K[0][i] * B1 + K[2][i] * B3 + K[3][i] * B4 +
                               K[4][i] * B5 + K[5][i] * B6);
    rhs(c, s, t + h, y_new, K[6]);
}

static inline double error_norm(const double K[7][2], double h,
                                const double *y, const double *y_new,
                                double rtol, double atol)
{
    double acc = 0.0;
    for (int i = 0; i < 2; i++) {
        double err = (K[0][i] * E1 + K[2][i] * E3 + K[3][i] * E4 +
                      K[4][i] * E5 + K[5][i] * E6 + K[6][i] * E7) * h;
        double sc = atol + fmax(fabs(y[i]), fabs(y_new[i])) * rtol;
        double r = err / sc;
        acc += r * r;
    }
    return sqrt(acc / 2.0);
}

static inline double step_factor(double err, int rejected)
{
    if (err < 1.0) {
        double f = err == 0.0 ? MAX_FACTOR
                              : fmin(MAX_FACTOR, SAFETY * pow(err, ERR_EXP));
        return rejected ? fmin(1.0, f) : f;
    }
    return fmax(MIN_FACTOR, SAFETY * pow(err, ERR_EXP));
}

/* SciPy's select_initial_step (forward); 1 rhs call */
static double initial_step(const Case *c, int s, double t0, const double *y0,
                           double t_bound, const double *f0)
{
    double len = fabs(t_bound - t0);
    if (len == 0.0)
        return 0.0;
    double d0 = 0.0, d1 = 0.0, sc[2];
    for (int i = 0; i < 2; i++) {
        sc[i] = c->atol + fabs(y0[i]) * c->rtol;
        double a = y0[i] / sc[i], b = f0[i] / sc[i];
        d0 += a * a;
        d1 += b * b;
    }
    d0 = sqrt(d0 / 2.0);
    d1 = sqrt(d1 / 2.0);
    double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    h0 = fmin(h0, len);
    double y1[2], f1[2];
    for (int i = 0; i < 2; i++)
        y1[i] = y0[i] + h0 * f0[i];
    rhs(c, s, t0 + h0, y1, f1);
    double d2 = 0.0;
    for (int i = 0; i < 2; i++) {
        double a = (f1[i] - f0[i]) / sc[i];
        d2 += a * a;
    }
    d2 = sqrt(d2 / 2.0) / h0;
    double h1 = (d1 <= 1e-15 && d2 <= 1e-15) ? fmax(1e-6, h0 * 1e-3)
                                             : pow(0.01 / fmax(d1, d2), 0.2);
    return fmin(fmin(100.0 * h0, h1), len);
}

typedef struct {
    double t_old, h, y_old[2], Q[2][4];
} Dense;

static inline void dense_init(Dense *D, const double K[7][2], double t,
                              double h, const double *y)
{
    D->t_old = t;
    D->h = h;
    for (int i = 0; i < 2; i++) {
        D->y_old[i] = y[i];
        for (int k = 0; k < 4; k++) {
            double acc = K[0][i] * PD[0][k];
            for (int j = 2; j < 7; j++)
                acc += K[j][i] * PD[j][k];
            D->Q[i][k] = acc;
        }
    }
}

static inline void dense_eval(const Dense *D, double t, double *out)
{
    double x = (t - D->t_old) / D->h;
    double x2 = x * x, x3 = x2 * x, x4 = x3 * x;
    for (int i = 0; i < 2; i++)
        out[i] = D->y_old[i] + D->h * (D->Q[i][0] * x + D->Q[i][1] * x2 +
                                       D->Q[i][2] * x3 + D->Q[i][3] * x4);
}

static inline double ev_at(const Case *c, const Disc *d, const Dense *D,
                           int k, double t, double *gd)
{
    double y[2], g;
    dense_eval(D, t, y);
    event(c, d, k, t, y, &g, gd);
    return g;
}

/* root of event k bracketed as g(lo) > 0 >= g(hi): Illinois regula falsi
 * with a midpoint every 4th trial; returns the first point on the event
 * side, *ok = 0 if the iteration cap was reached */
static double root_falsi(const Case *c, const Disc *d, const Dense *D, int k,
                         double lo, double hi, double glo, double ghi, int *ok)
{
    int side = 0;
    double gd;
    for (int it = 0; it < MAX_FALSI; it++) {
        double tol = 4.0 * EPS_MACH * fmax(fmax(fabs(lo), fabs(hi)), 1.0);
        if (hi - lo <= tol) {
            *ok = 1;
            return hi;
        }
        double m = falsi_point(lo, hi, glo, ghi, tol, it % 4 == 3);
        double g = ev_at(c, d, D, k, m, &gd);
        if (g > 0.0) {
            if (side == 1)
                ghi *= 0.5;
            lo = m;
            glo = g;
            side = 1;
        } else {
            if (side == -1)
                glo *= 0.5;
            hi = m;
            ghi = g;
            side = -1;
        }
    }
    *ok = 0;
    return hi;
}

/* where dg/dt changes sign: sign*gd < 0 at lo, > 0 at hi (bisection) */
static double extremum(const Case *c, const Disc *d, const Dense *D, int k,
                       double lo, double hi, double sign)
{
    double gd;
    for (int it = 0; it < MAX_BISECT; it++) {
        double tol = 4.0 * EPS_MACH * fmax(fmax(fabs(lo), fabs(hi)), 1.0);
        if (hi - lo <= tol)
            break;
        double mid = 0.5 * (lo + hi);
        ev_at(c, d, D, k, mid, &gd);
        if (sign * gd < 0.0)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

static inline int bracket_kind(int terminal, int phase_start, double g0,
                               double gd0, double g1, double gd1)
{
    if (g0 > 0.0) {
        if (g1 <= 0.0)
            return SIGN_CHANGE;
        if (gd0 < 0.0 && gd1 > 0.0)
            return SEARCH_MIN; /* interior minimum: a crossing and return? */
        return NO_ROOT;
    }
    if (terminal && phase_start && g1 <= 0.0) {
        if (gd0 >= 0.0 && gd1 < 0.0)
            return SEARCH_MAX; /* left the surface and came back? */
        return AT_START;
    }
    return NO_ROOT;
}

static double locate(const Case *c, const Disc *d, const Dense *D, int k,
                     int kind, double ta, double tb, double g0, double g1,
                     int *ok)
{
    double lo = ta, hi = tb, glo = g0, ghi = g1, gd;
    if (kind != SIGN_CHANGE) {
        double sign = kind == SEARCH_MIN ? 1.0 : -1.0;
        double tm = extremum(c, d, D, k, ta, tb, sign);
        double gm = ev_at(c, d, D, k, tm, &gd);
        if (sign > 0.0) {
            if (gm > 0.0) {
                *ok = 1;
                return INFINITY;
            }
            hi = tm;
            ghi = gm;
        } else {
            if (gm <= 0.0) {
                *ok = 1;
                return ta; /* never left the surface */
            }
            lo = tm;
            glo = gm;
        }
    }
    return root_falsi(c, d, D, k, lo, hi, glo, ghi, ok);
}

/* ---- one run ------------------------------------------------------------------------ */
static int run_case(const Case *c, Met *m)
{
    const int n_ev = c->wall ? N_EV_MAX : N_EV_MAX - 1;
    Disc d = {MODE_REST, 1, 1};
    double y[2] = {0.0, 0.0}, y_new[2], f[2], K[7][2];
    double g0[N_EV_MAX], gd0[N_EV_MAX], g1[N_EV_MAX], gd1[N_EV_MAX];
    double roots[N_EV_MAX];
    Dense D;

    m->max_abs = 0.0;
    m->impacts = m->wall_impacts = 0.0;
    m->t_uplift = NAN;
    m->t_pass_alpha = NAN;
    m->t_last_impact = -INFINITY;
    m->t_final = NAN;
    m->nfev = m->nsteps = 0.0;

    double t = 0.0, t_end = c->t_end, h_abs = 0.0, t_phase = NAN;
    double steps_taken = 0.0;
    int status = RUNNING, zero_length = 0, at_break = 0;

    while (status == RUNNING) {
        if (t_phase == t) {
            if (++zero_length > MAX_ZERO_LENGTH) {
                status = FAIL_TRANSITIONS;
                break;
            }
        } else {
            zero_length = 0;
        }
        t_phase = t;

        /* static phase: only the excitation can end it */
        if (d.stat) {
            double t_stop = fmin(t_end, c->dur), t_hit = INFINITY;
            if (t < t_stop || (t == t_stop && t < t_end))
                t_hit = static_exit(c, &d, t, t_stop);
            if (!isfinite(t_hit)) {
                t = t_end;
                status = after_step(c, &d, m, t, y, 1);
                break;
            }
            t = t_hit;
            status = transition(c, &d, m, -1, t, y);
            at_break = 0;
            h_abs = 0.0;
            continue;
        }

        /* continuous phase */
        rhs(c, d.pivot, at_break ? next_up(t) : t, y, f);
        m->nfev += 1;
        if (h_abs == 0.0) {
            double t_bound = fmin(next_breakpoint(c, t), t_end);
            h_abs = initial_step(c, d.pivot, t, y, t_bound, f);
            m->nfev += 1;
        }
        for (int k = 0; k < n_ev; k++)
            event(c, &d, k, t, y, &g0[k], &gd0[k]);
        int phase_start = 1;

        for (;;) {
            double t_bp = next_breakpoint(c, t);
            double t_bound = fmin(t_bp, t_end), t_new, h;
            if (steps_taken >= c->max_steps) {
                status = FAIL_STEP_BUDGET;
                break;
            }
            /* adaptive step (SciPy RK45) */
            double min_step = 10.0 * fabs(ulp(t));
            if (h_abs < min_step)
                h_abs = min_step;
            int rejected = 0, failed = 0;
            for (;;) {
                if (h_abs < min_step) {
                    failed = 1;
                    status = FAIL_STEP_UNDERFLOW;
                    break;
                }
                if (steps_taken >= c->max_steps) {
                    failed = 1;
                    status = FAIL_STEP_BUDGET;
                    break;
                }
                t_new = t + h_abs;
                if (t_new > t_bound)
                    t_new = t_bound;
                h = t_new - t;
                h_abs = fabs(h);
                rk_step(c, d.pivot, t, y, f, h, K, y_new);
                m->nfev += 6;
                steps_taken += 1.0;
                double err = error_norm(K, h, y, y_new, c->rtol, c->atol);
                if (!isfinite(err))
                    err = INFINITY;
                if (err < 1.0) {
                    h_abs *= step_factor(err, rejected);
                    break;
                }
                h_abs *= step_factor(err, 1);
                rejected = 1;
            }
            if (failed)
                break;
            m->nsteps += 1;

            /* events on [t, t_new] */
            for (int k = 0; k < n_ev; k++)
                event(c, &d, k, t_new, y_new, &g1[k], &gd1[k]);
            dense_init(&D, K, t, h, y);
            double t_term = INFINITY;
            int k_term = -1, ev_failed = 0;
            for (int k = 0; k < n_ev; k++) {
                roots[k] = INFINITY;
                if (!isfinite(g0[k]) && !isfinite(g1[k]))
                    continue;
                int kind = bracket_kind(TERMINAL[k], phase_start, g0[k],
                                        gd0[k], g1[k], gd1[k]);
                if (kind == NO_ROOT)
                    continue;
                double r;
                int ok = 1;
                if (kind == AT_START)
                    r = t;
                else
                    r = locate(c, &d, &D, k, kind, t, t_new, g0[k], g1[k], &ok);
                if (!ok)
                    ev_failed = 1;
                roots[k] = r;
                if (TERMINAL[k] && r < t_term) {
                    t_term = r;
                    k_term = k;
                }
            }
            if (ev_failed) {
                status = FAIL_EVENT;
                break;
            }
            /* observers: max |theta| at a peak, first passage of alpha */
            if (roots[EV_PEAK] <= t_term && isfinite(roots[EV_PEAK])) {
                double yev[2];
                dense_eval(&D, roots[EV_PEAK], yev);
                track(m, yev[0]);
            }
#ifndef NO_PASS_ALPHA
            if (roots[EV_PASS] <= t_term && isfinite(roots[EV_PASS]) &&
                isnan(m->t_pass_alpha))
                m->t_pass_alpha = roots[EV_PASS];
#endif

            if (k_term >= 0) {
                if (t_term >= t_new) {
                    y[0] = y_new[0];
                    y[1] = y_new[1];
                } else {
                    dense_eval(&D, t_term, y);
                }
                t = t_term;
                status = transition(c, &d, m, k_term, t, y);
                at_break = t == t_bp;
                h_abs = 0.0;
                break;
            }

            t = t_new;
            y[0] = y_new[0];
            y[1] = y_new[1];
            f[0] = K[6][0];
            f[1] = K[6][1];
            for (int k = 0; k < n_ev; k++) {
                g0[k] = g1[k];
                gd0[k] = gd1[k];
            }
            phase_start = 0;
            if (t >= t_end) {
                status = after_step(c, &d, m, t, y, 1);
                break;
            }
            status = after_step(c, &d, m, t, y, 0);
            if (status != RUNNING)
                break;
            if (t == t_bp) {
                /* the pulse ends here: restart from the right limit */
                rhs(c, d.pivot, next_up(t), y, f);
                m->nfev += 1;
                for (int k = 0; k < n_ev; k++)
                    event(c, &d, k, t, y, &g0[k], &gd0[k]);
            }
        }
    }
    if (isnan(m->t_final))
        m->t_final = t;
    return status;
}

/* ---- the grid entry --------------------------------------------------------------- */
/*
 * Runs n one-sine cases.  par[0..8]: alpha, p, e, g, theta_over, wall side w
 * (+1/-1), theta_w (inf: no contact), e_w, hogan (1: gap 0); wall: 0 for the
 * two-sided block (par[5..8] ignored), 1 for the wall model.  Per case i:
 * pulse amplitude amp[i] >= 0 [m/s^2], omega[i] [rad/s], sign[i] (+1/-1),
 * t_end[i] (the pulse lasts 2 pi / omega[i]).  opt[0..5]: rtol, atol,
 * eps_omega, eps_t, early (0/1), max_steps.  Outputs per case: status,
 * max |theta| [rad], nfev, nsteps (accepted); impacts, wall_impacts and
 * t_pass_alpha [s] (NaN: never; always NaN with -DNO_PASS_ALPHA) may be
 * NULL.  Returns the number of failed runs.
 */
int rock_grid(long n, const double *par, int wall, const double *amp,
              const double *omega, const double *sign, const double *t_end,
              const double *opt, int32_t *status, double *max_theta,
              int64_t *nfev, int64_t *nsteps, double *impacts,
              double *wall_impacts, double *t_pass_alpha)
{
    Case c;
    int n_failed = 0;
    c.alpha = par[0];
    c.p = par[1];
    c.e = par[2];
    c.g = par[3];
    c.theta_over = par[4];
    c.tan_alpha = tan(c.alpha);
    c.wall = wall != 0;
    c.wside = par[5] > 0.0 ? 1.0 : -1.0;
    c.theta_w = par[6];
    c.e_w = par[7];
    c.hogan = c.wall && par[8] != 0.0;
    c.rtol = opt[0];
    c.atol = opt[1];
    c.eps_omega = opt[2];
    c.eps_t = opt[3];
    c.early = opt[4] != 0.0;
    c.max_steps = opt[5];
    for (long i = 0; i < n; i++) {
        Met m;
        c.amp = sign[i] * amp[i];
        c.omega = omega[i];
        c.dur = 2.0 * PI / omega[i];
        c.t_end = t_end[i];
        int st = run_case(&c, &m);
        status[i] = st;
        max_theta[i] = m.max_abs;
        nfev[i] = (int64_t)m.nfev;
        nsteps[i] = (int64_t)m.nsteps;
        if (impacts)
            impacts[i] = m.impacts;
        if (wall_impacts)
            wall_impacts[i] = m.wall_impacts;
        if (t_pass_alpha)
            t_pass_alpha[i] = m.t_pass_alpha;
        if (st < 0)
            n_failed++;
    }
    return n_failed;
}
