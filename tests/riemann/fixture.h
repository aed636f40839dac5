/* The cmocka group fixture of the riemann/ tests: default parameters, one workspace, GSL's
 * aborting error handler off (riemann.h). */
#ifndef SABRE_TESTS_RIEMANN_FIXTURE_H
#define SABRE_TESTS_RIEMANN_FIXTURE_H

#include <gsl/gsl_errno.h>

#include "sabre/riemann.h"
#include "testutil.h"

struct fixture {
  struct rmn_workspace *ws;
  struct rmn_params par;
};

static int setup(void **state) {
  static struct fixture f;
  gsl_set_error_handler_off();
  f.ws = rmn_workspace_alloc();
  rmn_params_default(&f.par);
  *state = &f;
  return f.ws ? 0 : -1;
}

static int teardown(void **state) {
  rmn_workspace_free(((struct fixture *)*state)->ws);
  return 0;
}

#endif
