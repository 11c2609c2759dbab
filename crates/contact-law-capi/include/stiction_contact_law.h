/*
 * stiction_contact_law.h - C ABI of the Rust crate contact-law (crate contact-law-capi).
 *
 * The adhesive-contact law p(d; d_min, path) of a rough surface, tabulated in law.json,
 * for finite-element codes. SI units: separations d in m, pressure in Pa (compressive
 * positive, adhesive negative), tangent dp/dd in Pa/m. d is measured from the mean plane
 * of asperity heights to the counter-flat: smaller d is deeper contact.
 *
 * Every function returns an SCL_* status. SCL_OK (0) is success inside the measured region
 * of the table; the evaluations return SCL_BEYOND_REACH or SCL_ABOVE_TABLE, with their
 * outputs written, for a point outside it (SCL_HAS_VALUE(status) is true for all three);
 * the SCL_ERR_* codes write nothing. A null required pointer gives SCL_ERR_NULL.
 * scl_last_error() explains the last failure on the calling thread. A loaded law is
 * immutable and may be evaluated from several threads at once, each with its own
 * scl_state.
 *
 * Hand-written; the tests of contact-law-capi check it against the library's exports,
 * constants and struct layout. Documentation: docs/contact-law.md.
 */
#ifndef STICTION_CONTACT_LAW_H
#define STICTION_CONTACT_LAW_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SCL_ABI_VERSION 2

/* Status codes. */
enum scl_status {
    SCL_OK = 0,
    SCL_ERR_NULL = 1,         /* a required pointer argument was null */
    SCL_ERR_IO = 2,           /* the file could not be read (missing, unreadable, too large) */
    SCL_ERR_FORMAT = 3,       /* not a valid law.json (syntax, format, version, a value) */
    SCL_ERR_OUT_OF_RANGE = 4, /* separation or history outside the tabulated range */
    SCL_ERR_INVALID = 5,      /* non-finite d, unknown path, inconsistent state */
    SCL_ERR_INTERNAL = 6,     /* internal error (caught panic): please report */
    /* Not errors: outputs written, but the point lies outside the measured region. */
    SCL_BEYOND_REACH = 7, /* beyond the curve's reach: pressure and tangent exactly 0 (no
                             asperity in contact: the model's own value, not interpolated) */
    SCL_ABOVE_TABLE = 8   /* history shallower than the table: the law's blend of the
                             shallowest branch towards zero at the virgin reach, not measured
                             (pressures of the order of the file's pressure_floor or less) */
};

/* True for the statuses whose outputs are written: SCL_OK, SCL_BEYOND_REACH, SCL_ABOVE_TABLE. */
#define SCL_HAS_VALUE(status) ((status) == SCL_OK || (status) == SCL_BEYOND_REACH || (status) == SCL_ABOVE_TABLE)

/* scl_state.path */
enum scl_path {
    SCL_PATH_APPROACH = 0, /* coming from far or reloading */
    SCL_PATH_RETRACT = 1   /* retracting after a reversal */
};

/* scl_state.flags bits */
#define SCL_STATE_TOUCHED 1 /* loaded: d_min, last_d and path are valid */
#define SCL_STATE_TURNED 2  /* d_turn is valid: the current path began at a reversal */

/* Opaque handle of a loaded law. */
typedef struct scl_law scl_law;

/*
 * History of one point of the surface, owned by the caller. All-zero bytes is a virgin
 * surface (no call needed for zero-initialised storage); every stored number is finite.
 * In an implicit FE code evaluate with a copy of the state of the last converged
 * increment and keep the updated copy only when the increment converges.
 */
typedef struct scl_state {
    double d_min;  /* deepest separation reached (m), valid with SCL_STATE_TOUCHED */
    double last_d; /* separation of the previous call (m), valid with SCL_STATE_TOUCHED */
    double d_turn; /* separation of the last reversal (m), valid with SCL_STATE_TURNED */
    int32_t path;  /* SCL_PATH_APPROACH or SCL_PATH_RETRACT */
    int32_t flags; /* SCL_STATE_TOUCHED | SCL_STATE_TURNED */
} scl_state;

/* Reads and validates law.json; *out receives a handle to free with scl_law_free. */
int scl_law_load(const char *path, scl_law **out);

/* Frees a handle; NULL is a no-op. */
void scl_law_free(scl_law *law);

/* Sets *state to a virgin surface (all zero); NULL is a no-op. */
void scl_state_init(scl_state *state);

/*
 * Pressure and tangent at separation d (m), updating *state:
 *  - d < d_min: the approach deepens the history (d_min = d), virgin envelope;
 *  - otherwise a reversal switches the path (approach and d > last d: retract;
 *    retract and d < last d: approach), then that branch of the current d_min.
 * Returns SCL_OK in the measured region, SCL_BEYOND_REACH or SCL_ABOVE_TABLE outside it
 * (outputs and state written), SCL_ERR_OUT_OF_RANGE for a history deeper than the table.
 *
 * Positive retract tangents: a law whose file has the key "positive_retract_tangent" has
 * retract branches on which the pressure rises as the gap opens before the pull-out (the
 * eq-12 reload overshoot of soft films; "bounded" reload removes it): there the tangent
 * returned is > 0 on the retract path, which an implicit FE code receives as a negative
 * unloading stiffness. Use min(tangent, 0) as the Newton stiffness on the retract path
 * (the pressure itself is right), or tabulate with contact.reload = "bounded".
 */
int scl_law_eval(const scl_law *law, double d, scl_state *state, double *pressure,
                 double *tangent);

/*
 * Stateless: branch `path` of history d_min (INFINITY for a virgin surface) at d; when
 * d < d_min the history deepens and the virgin envelope applies. d_min_out (may be NULL)
 * receives the history after the call.
 */
int scl_law_eval_stateless(const scl_law *law, double d, double d_min, int32_t path,
                           double *pressure, double *tangent, double *d_min_out);

/* The tabulated d_min range (m); deeper histories are out of range. */
int scl_law_d_min_range(const scl_law *law, double *lo, double *hi);

/* *exact = 1 if the one-number history is exact for *state, 0 after a partial reload or a
 * partial retraction (the law then follows the branch of d_min). The status is the
 * region of the state's history d_min: SCL_OK inside the table (or a virgin state),
 * SCL_ABOVE_TABLE shallower than it (*exact written; the law there is not measured),
 * SCL_BEYOND_REACH at or beyond the virgin reach (never in contact), and
 * SCL_ERR_OUT_OF_RANGE deeper than the table (nothing written). */
int scl_law_history_exact(const scl_law *law, const scl_state *state, int *exact);

/* Message of the last failed call on this thread ("" if none); valid until the next
 * failing call on this thread. */
const char *scl_last_error(void);

/* Copies that message into buf (at most len bytes with the NUL) and returns its full
 * length without the NUL. */
size_t scl_last_error_copy(char *buf, size_t len);

/* SCL_ABI_VERSION of the library: compare with the header's at start-up. */
int scl_abi_version(void);

#ifdef __cplusplus
}
#endif

#endif /* STICTION_CONTACT_LAW_H */
