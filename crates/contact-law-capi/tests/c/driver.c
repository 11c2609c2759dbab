/* Test driver of the C ABI: compiled and run by tests/c_abi.rs against the static library.
 * argv[1]: a law.json. Prints the layout of scl_state, the constants, the error paths, then
 * executes commands read from stdin:
 *   e D            stateful evaluation at D          -> "e rc p t d_min last_d d_turn path flags"
 *   s D DMIN PATH  stateless evaluation              -> "s rc p t d_min_out"
 *   x              is the history exact?             -> "x rc exact"
 *   r              reset the state to virgin         -> "r"
 * Numbers are printed with %.17g, which reads back to the same double. */
#include "stiction_contact_law.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

int main(int argc, char **argv) {
    scl_law *law = NULL;
    scl_state st;
    double p = 0.0, t = 0.0, dm = 0.0, lo = 0.0, hi = 0.0;
    int rc, exact = -1;
    char op;
    char small[8];
    size_t full;

    if (argc != 2) {
        fprintf(stderr, "usage: driver law.json < commands\n");
        return 2;
    }
    printf("layout %zu %zu %zu %zu %zu %zu\n", sizeof(scl_state), offsetof(scl_state, d_min),
           offsetof(scl_state, last_d), offsetof(scl_state, d_turn), offsetof(scl_state, path),
           offsetof(scl_state, flags));
    printf("consts %d %d %d %d %d %d %d %d %d %d %d %d %d %d %d\n", SCL_OK, SCL_ERR_NULL,
           SCL_ERR_IO, SCL_ERR_FORMAT, SCL_ERR_OUT_OF_RANGE, SCL_ERR_INVALID, SCL_ERR_INTERNAL,
           SCL_BEYOND_REACH, SCL_ABOVE_TABLE, SCL_PATH_APPROACH, SCL_PATH_RETRACT,
           SCL_STATE_TOUCHED, SCL_STATE_TURNED, SCL_ABI_VERSION, scl_abi_version());
    printf("has_value %d %d %d %d %d\n", SCL_HAS_VALUE(SCL_OK), SCL_HAS_VALUE(SCL_BEYOND_REACH),
           SCL_HAS_VALUE(SCL_ABOVE_TABLE), SCL_HAS_VALUE(SCL_ERR_OUT_OF_RANGE),
           SCL_HAS_VALUE(SCL_ERR_INVALID));

    /* error paths: codes, untouched outputs, messages */
    rc = scl_law_load(NULL, &law);
    printf("load_null %d %d %d\n", rc, law == NULL, (int)strlen(scl_last_error()) > 0);
    rc = scl_law_load(argv[1], NULL);
    printf("load_null_out %d\n", rc);
    rc = scl_law_load("/nonexistent-dir/law.json", &law);
    printf("load_missing %d %d %d\n", rc, law == NULL, strstr(scl_last_error(), "nonexistent-dir") != NULL);
    full = scl_last_error_copy(small, sizeof small);
    printf("copy %d %d %d\n", full == strlen(scl_last_error()), (int)strlen(small) == (int)sizeof small - 1,
           strncmp(small, scl_last_error(), sizeof small - 1) == 0);
    printf("copy_null %d\n", scl_last_error_copy(NULL, 0) == full);
    scl_law_free(NULL);
    scl_state_init(NULL);

    rc = scl_law_load(argv[1], &law);
    printf("load %d\n", rc);
    if (rc != SCL_OK) {
        fprintf(stderr, "load failed: %s\n", scl_last_error());
        return 1;
    }
    scl_state_init(&st);
    printf("eval_null %d %d %d %d\n", scl_law_eval(NULL, 1e-9, &st, &p, &t),
           scl_law_eval(law, 1e-9, NULL, &p, &t), scl_law_eval(law, 1e-9, &st, NULL, &t),
           scl_law_eval(law, 1e-9, &st, &p, NULL));
    printf("stateless_null %d %d\n", scl_law_eval_stateless(NULL, 1e-9, 1e-9, 0, &p, &t, NULL),
           scl_law_eval_stateless(law, 1e-9, 1e-9, 0, NULL, &t, NULL));
    rc = scl_law_d_min_range(law, &lo, &hi); /* outputs read in a later statement */
    printf("range %d %.17g %.17g %d\n", rc, lo, hi, scl_law_d_min_range(law, NULL, &hi));
    printf("exact_null %d\n", scl_law_history_exact(law, NULL, &exact));
    {
        scl_state bad = st;
        bad.flags = SCL_STATE_TOUCHED;
        bad.path = 7;
        printf("bad_state %d\n", scl_law_eval(law, 1e-9, &bad, &p, &t));
        printf("bad_path %d\n", scl_law_eval_stateless(law, 1e-9, 1e-9, 3, &p, &t, NULL));
    }

    while (scanf(" %c", &op) == 1) {
        double d = 0.0, dmin = 0.0;
        int path = 0;
        p = t = dm = 0.0;
        if (op == 'e') {
            if (scanf("%lf", &d) != 1) return 3;
            rc = scl_law_eval(law, d, &st, &p, &t);
            printf("e %d %.17g %.17g %.17g %.17g %.17g %d %d\n", rc, p, t, st.d_min, st.last_d,
                   st.d_turn, (int)st.path, (int)st.flags);
        } else if (op == 's') {
            if (scanf("%lf %lf %d", &d, &dmin, &path) != 3) return 3;
            rc = scl_law_eval_stateless(law, d, dmin, path, &p, &t, &dm);
            printf("s %d %.17g %.17g %.17g\n", rc, p, t, dm);
        } else if (op == 'x') {
            rc = scl_law_history_exact(law, &st, &exact);
            printf("x %d %d\n", rc, exact);
        } else if (op == 'r') {
            scl_state_init(&st);
            printf("r\n");
        } else {
            return 3;
        }
    }
    scl_law_free(law);
    return 0;
}
