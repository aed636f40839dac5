/*
 * Mass through the open boundaries (sabre/sph_open.h, docs/sph-solver.md §10):
 *   - the vertex masses J(14–15) against a hand computation: ṁ_v = Σ_s ρ_s |s| u_n,s / 2 over the
 *     vertex's open segments (2D), m^{n+1} = m^n + Δt ṁ* with ṁ* of the predictor's evaluation,
 *     wall vertices untouched;
 *   - conservation: fluid + vertex masses − the time-integrated boundary flux stays constant to
 *     round-off in a 2D box with one open face, for an imposed inflow velocity and for an imposed
 *     pressure that makes the fluid leave;
 *   - the i/o terms of the continuity J(11–13): in a uniform flow through a box open at both ends
 *     the fluid next to the inlet keeps its density with them, and loses it without them.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "kernel.h"
#include "open/open_internal.h"
#include "operators/pressure.h"
#include "sabre/common.h"
#include "sabre/sph_open.h"
#include "sabre/sph_solver.h"
#include "solver_fixture.h"
#include "testutil.h"

/* A 2D box 0.3 × 0.3 m with its right face open, water to 0.15 m (first row Δr from the walls). */
static const char box_case[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.025\n"
    "  first_row: 1\n"
    "  walls: [{type: box, lo: [0, 0], hi: [0.3, 0.3], open: [x+]}]\n"
    "  fluid: [{type: box, lo: [0, 0], hi: [0.3, 0.15]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "gravity: [0, -9.81]\n"
    "initial: {pressure: hydrostatic}\n"
    "time: {end: 1}\n"
    "open_boundaries:\n  - {name: right, wall: 0, %s}\n";

static struct sph_solver *box_solver(const char *open) {
  char text[4096];
  snprintf(text, sizeof text, box_case, open);
  return fixture_solver_from_case(text);
}

static double total_mass(const struct sph_solver *sv) {
  double m = 0.0;
  for (int k = SPH_KIND_FLUID; k <= SPH_KIND_VERTEX; k++) { /* fluid and vertices */
    const struct sph_parts *p = &sv->sys.part[k];
    for (size_t i = 0; i < p->n; i++) m += p->mass[i];
  }
  return m;
}

/* ṁ_v by hand from the store's solved segment values (the last evaluation): half of ρ_s |s| u_n,s
 * of the wet part of each open segment of a wet vertex, all of it when the segment's other vertex
 * is dry (above the surface); a corner takes none, and its half goes to no vertex. */
static double mdot_hand(const struct sph_solver *sv, size_t iv) {
  const struct sph_open *op = sv->open;
  const struct sph_parts *sg = &sv->sys.part[SPH_KIND_SEGMENT];
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  double sum = 0.0;
  for (size_t j = 0; j < sg->n; j++) {
    if (op->seg_group[j] < 0 || (sg->vertex[0][j] != iv && sg->vertex[1][j] != iv)) continue;
    const struct sph_open_points *pt = &op->pts[op->seg_group[j]];
    const size_t k = (size_t)op->seg_point[j];
    if (pt->slot[k] == (size_t)-1) continue; /* dry: no flux */
    if (v->flags[iv] & SPH_FLAG_CORNER) continue;
    if (!(pt->wet[op->vert_point[iv]] > 0.0)) continue; /* above the surface: nothing */
    const size_t other = sg->vertex[0][j] == iv ? sg->vertex[1][j] : sg->vertex[0][j];
    const int other_dry = !(v->flags[other] & SPH_FLAG_CORNER) &&
                          !(op->pts[op->vert_group[other]].wet[op->vert_point[other]] > 0.0);
    const double un = -sg->v[0][j]; /* the face x+: n = (−1, 0) */
    /* the segment's wet part only (test_open checks the fractions) */
    sum += (other_dry ? 1.0 : 0.5) * sg->rho[j] * sg->measure[j] * pt->wet[k] * un;
  }
  return sum;
}

static void test_vertex_mass_hand(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *sv = box_solver("impose: velocity, normal_velocity: 0.05");
  const struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  const struct sph_open *op = sv->open;
  double *m0 = malloc(v->n * sizeof *m0);
  for (size_t i = 0; i < v->n; i++) m0[i] = v->mass[i];
  char msg[1024];
  if (sph_solver_step(sv, 1.0, msg, sizeof msg) != 0) fail_msg("%s", msg);
  const double dt = sv->dt;
  /* The last evaluation of the step is the predictor's: its ṁ is what the corrector used. */
  size_t nopen = 0, nflux = 0, ncorner = 0;
  double err = 0.0, sum = 0.0;
  for (size_t i = 0; i < v->n; i++) {
    if (op->vert_group[i] < 0) {
      assert_true(v->mass[i] == m0[i]); /* walls: bitwise unchanged */
      assert_true(op->mdot[i] == 0.0);
      continue;
    }
    nopen++;
    const double hand = mdot_hand(sv, i);
    err = fmax(err, fabs(op->mdot[i] - hand) / (1000.0 * 0.025 * 0.05));
    assert_true(v->mass[i] == m0[i] + dt * op->mdot[i]); /* J(14), bitwise */
    sum += op->mdot[i];
    if (op->mdot[i] != 0.0) nflux++;
    /* the floor corner (0.3, 0) takes no mass, and its half of the corner segment's flux goes to
     * no vertex (the floor's vertex layer stands for that fluid); the vertex above it half of
     * each of its two segments: about ρ0 Δr u, as every vertex of the face below the surface */
    if (fabs(v->x[0][i] - 0.3) < 1e-12 && fabs(v->x[1][i]) < 1e-12) {
      ncorner++;
      assert_true(v->flags[i] & SPH_FLAG_CORNER);
      assert_true(op->mdot[i] == 0.0 && v->mass[i] == m0[i]);
    }
    if (fabs(v->x[0][i] - 0.3) < 1e-12 && fabs(v->x[1][i] - 0.025) < 1e-12) {
      const double expect = 1000.0 * 0.025 * 0.05;
      assert_true(fabs(op->mdot[i] - expect) <= 0.01 * expect); /* ρ_s within 1 % of ρ0 */
    }
  }
  print_message(
      "one step (dt = %.4g s): %zu open vertices, %zu with a flux, max |mdot - hand| %.3g of "
      "rho0 dr u; sum of mdot %.12g kg/s, group mass flux %.12g kg/s (imposed rho0 H u = %.6g)\n",
      dt, nopen, nflux, err, sum, op->stats[0].mass_flux, 1000.0 * 0.15 * 0.05);
  assert_int_equal(ncorner, 1);
  assert_true(nflux >= 6);
  assert_true(err <= 1e-14);
  assert_true(fabs(sum - op->stats[0].mass_flux) <= 1e-13 * fabs(sum));
  assert_true(fabs(op->mass_step[0] - dt * op->stats[0].mass_flux) == 0.0);
  double row[SPH_OPEN_CSV_COLUMNS];
  sph_open_csv_row(op, 0, sv->time, row);
  assert_string_equal(sph_open_csv_columns()[7], "mass_flux");
  assert_true(row[7] == op->stats[0].mass_flux);
  free(m0);
  fixture_solver_destroy(sv);
}

/* The floor of an outflow vertex's mass (sph_open_mass_set, outflow_deficit = 0.5 here): a vertex
 * the flux would take below m_base − 0.5 m_ref stops there, one already below it stays where it is
 * (never raised), one above it and inflow vertices follow J(14); the step's entered mass is the
 * vertices' change (Δt Σ ṁ plus the outflow the floor held back, which mass_withheld adds up). */
static void test_outflow_floor(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *sv = box_solver("impose: pressure, pressure: 0, outflow_deficit: 0.5");
  struct sph_open *op = sv->open;
  sph_solver_evaluate(sv);
  struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  const double m_ref = 1000.0 * 0.025 * 0.025, dt = 1e-3;
  assert_true(sv->cfg.open.group[0].outflow_deficit == 0.5);
  size_t iv[4], nv = 0;
  for (size_t i = 0; i < v->n; i++) {
    if (op->vert_group[i] < 0) continue;
    op->mdot[i] = 0.0;
    op->mass0[i] = v->mass[i] = v->wall_mass[i];
    if (!(v->flags[i] & SPH_FLAG_CORNER) && nv < 4) iv[nv++] = i;
  }
  assert_int_equal(nv, 4);
  const double *b = v->wall_mass;
  /* 0: from −0.4 m_ref by −0.3 m_ref: held at −0.5 (0.2 m_ref held back); 1: from −0.8 m_ref
   * (below the floor) by −0.1: stays; 2: from 0 by −0.3: follows; 3: inflow by +2 m_ref: follows */
  const double start[4] = {-0.4, -0.8, 0.0, 0.0}, change[4] = {-0.3, -0.1, -0.3, 2.0};
  double flux = 0.0;
  for (int k = 0; k < 4; k++) {
    op->mass0[iv[k]] = b[iv[k]] + start[k] * m_ref;
    op->mdot[iv[k]] = change[k] * m_ref / dt;
    flux += op->mdot[iv[k]];
  }
  /* the predictor's half step: vertex 0 reaches its floor (−0.55 asked), 1 stays at m0 */
  sph_open_mass_set(op, sv, 0.5 * dt);
  assert_true(fabs(v->mass[iv[0]] - (b[iv[0]] - 0.5 * m_ref)) <= 1e-15 * m_ref);
  assert_true(fabs(v->mass[iv[2]] - (b[iv[2]] - 0.15 * m_ref)) <= 1e-15 * m_ref);
  assert_true(v->mass[iv[1]] == op->mass0[iv[1]]);
  assert_true(v->mass[iv[3]] == op->mass0[iv[3]] + 0.5 * dt * op->mdot[iv[3]]);
  op->stats[0].mass_flux = flux;
  const double entered0 = op->mass_entered[0], withheld0 = op->mass_withheld[0];
  sph_open_mass_end(op, sv, dt);
  const double expect[4] = {-0.5, -0.8, -0.3, 2.0};
  for (int k = 0; k < 4; k++)
    assert_true(fabs(v->mass[iv[k]] - (b[iv[k]] + expect[k] * m_ref)) <= 1e-14 * m_ref);
  const double held = 0.2 * m_ref + 0.1 * m_ref;
  assert_true(fabs(op->mass_withheld[0] - withheld0 - held) <= 1e-14 * m_ref);
  assert_true(fabs(op->mass_step[0] - (dt * flux + held)) <= 1e-14 * m_ref);
  assert_true(op->mass_entered[0] - entered0 == op->mass_step[0]);
  double change_sum = 0.0;
  for (size_t i = 0; i < v->n; i++)
    if (op->vert_group[i] >= 0) change_sum += v->mass[i] - op->mass0[i];
  assert_true(fabs(change_sum - op->mass_step[0]) <= 1e-14 * m_ref);
  double row[SPH_OPEN_CSV_COLUMNS];
  sph_open_csv_row(op, 0, sv->time, row);
  assert_string_equal(sph_open_csv_columns()[17], "mass_withheld");
  assert_true(row[17] == op->mass_withheld[0]);
  print_message("outflow floor at m_base - 0.5 m_ref: %.6g particle masses held back\n",
                (op->mass_withheld[0] - withheld0) / m_ref);
  fixture_solver_destroy(sv);
}

/* Run to t_end; return max |M(t) − M(0) − ∫ flux + released| / M(0) over the steps (released:
 * the mass that left with particles deleted at outflow vertices beyond what those took back),
 * with ∫ flux both the sum of the steps' mass_step and the groups' cumulative mass_entered (the
 * open CSVs' column, by which a case checks its balance). */
static double conservation(struct sph_solver *sv, double t_end, double *flux_total) {
  const double m_start = total_mass(sv);
  double in = 0.0, worst = 0.0, released0 = 0.0, entered0 = 0.0;
  for (int g = 0; g < sv->open->ngroups; g++) {
    released0 += sv->open->mass_released[g];
    entered0 += sv->open->mass_entered[g];
  }
  char msg[1024];
  long steps = 0;
  while (sv->time < t_end - 1e-12) {
    if (sph_solver_step(sv, t_end - sv->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
    double released = -released0, entered = -entered0;
    for (int g = 0; g < sv->open->ngroups; g++) {
      in += sv->open->mass_step[g];
      released += sv->open->mass_released[g];
      entered += sv->open->mass_entered[g];
    }
    worst = fmax(worst, fabs(total_mass(sv) - m_start - in + released) / m_start);
    worst = fmax(worst, fabs(total_mass(sv) - m_start - entered + released) / m_start);
    steps++;
  }
  *flux_total = in;
  print_message("  %ld steps to t = %g s: mass in %.6g kg of %.6g kg; max |M - M0 - in|/M0 %.3g\n",
                steps, sv->time, in, m_start, worst);
  return worst;
}

static void test_conservation(void **state) {
  (void)state;
  sabre_fp_traps_on();
  double in;
  struct sph_solver *sv = box_solver("impose: velocity, normal_velocity: 0.05");
  print_message("inflow at 0.05 m/s:\n");
  const double e_in = conservation(sv, 0.03, &in);
  /* about ρ0 H u t = 1000 × 0.15 × 0.05 × 0.03 = 0.225 kg/m entered (more: the wet face is higher)
   */
  assert_true(in > 0.2 && in < 0.45);
  assert_true(e_in <= 1e-13);
  fixture_solver_destroy(sv);
  /* an outlet at the hydrostatic pressure of a lower level: the fluid leaves */
  sv = box_solver("impose: pressure, hydrostatic: {depth: 0.1}");
  print_message("pressure outflow (hydrostatic, depth 0.1 m against 0.15 m of water):\n");
  const double e_out = conservation(sv, 0.03, &in);
  assert_true(in < 0.0);
  assert_true(e_out <= 1e-13);
  fixture_solver_destroy(sv);
}

/* Uniform flow at U through a box open at both ends, no gravity: the fluid next to the inlet
 * moves away from the inlet's vertices; the i/o terms J(11) give back what that motion takes from
 * Σ m_b w_ab and adds to γ (next to the floor and the lid, with the floor's and lid's vertex layers
 * sliding along with the inlet). Returns the max |ρ/ρ0 − 1| over the fluid within 2h of the
 * inlet. */
static double uniform_flow(int io_terms, double t_end) {
  static const char text[] =
      "geometry:\n"
      "  dimension: 2\n"
      "  dr: 0.025\n"
      "  first_row: 1\n"
      "  walls: [{type: box, lo: [0, 0], hi: [0.4, 0.4], open: [x-, x+]}]\n"
      "  fluid: [{type: box, lo: [0, 0], hi: [0.4, 0.4]}]\n"
      "fluid: {rho0: 1000, c0: 20}\n"
      "initial: {velocity: [0.05, 0]}\n"
      "time: {end: 1}\n"
      "open_boundaries:\n"
      "  - {name: in, wall: 0, faces: [x-], impose: velocity, normal_velocity: 0.05}\n"
      "  - {name: out, wall: 0, faces: [x+], impose: pressure, pressure: 0}\n";
  struct sph_solver *sv = fixture_solver_from_case(text);
  sv->open->no_io_terms = !io_terms;
  char msg[1024];
  while (sv->time < t_end - 1e-12)
    if (sph_solver_step(sv, t_end - sv->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  double worst = 0.0;
  size_t count = 0;
  for (size_t a = 0; a < f->n; a++)
    if (f->x[0][a] < 2.0 * sv->sys.h) { /* the corners with the floor and the lid included */
      worst = fmax(worst, fabs(f->rho[a] / 1000.0 - 1.0));
      count++;
    }
  print_message("  h = %g m, %zu of %zu particles near the inlet, %ld steps\n", sv->sys.h, count,
                f->n, sv->step);
  fixture_solver_destroy(sv);
  return worst;
}

static void test_io_terms(void **state) {
  (void)state;
  sabre_fp_traps_on();
  const double t_end = 0.03;
  const double with = uniform_flow(1, t_end), without = uniform_flow(0, t_end);
  print_message(
      "uniform flow 0.05 m/s through a box open at both ends, to t = %g s: max |rho/rho0 - 1| "
      "within 2h of the inlet (corners included) %.3g with the i/o terms of J(11), %.3g "
      "without\n",
      t_end, with, without);
  assert_true(with <= 1e-6 && without >= 1e-4); /* with: the trapezoidal rule of J(11) */
}

/* Creation and deletion by hand: a vertex given 1.25 particle masses (ρ_v Δr², ρ_v its solved
 * density) above its wall mass creates
 * one particle Δr/2 in front of it; a particle put behind the open face is deleted and its mass
 * goes to the two vertices of the segment it crossed (inflow vertices, J 14), or brings them back
 * towards their wall masses by its weights and the rest is released (outflow vertices). */
static void test_create_delete_hand(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *sv = box_solver("impose: velocity, normal_velocity: 0.05");
  struct sph_open *op = sv->open;
  sph_solver_evaluate(sv);
  struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX], *f = &sv->sys.part[SPH_KIND_FLUID];
  const double m_ref = 1000.0 * 0.025 * 0.025, m_start = total_mass(sv);
  assert_true(fabs(op->cell_volume - 0.025 * 0.025) <= 1e-15 * 0.025 * 0.025);
  size_t iv = (size_t)-1, iu = (size_t)-1;
  for (size_t i = 0; i < v->n; i++) {
    if (fabs(v->x[0][i] - 0.3) < 1e-12 && fabs(v->x[1][i] - 0.075) < 1e-12) iv = i;
    if (fabs(v->x[0][i] - 0.3) < 1e-12 && fabs(v->x[1][i] - 0.1) < 1e-12) iu = i;
  }
  assert_true(iv != (size_t)-1 && iu != (size_t)-1);
  const double base = v->wall_mass[iv];
  /* the boundary's density, say 3 % above ρ0 (a pressure level): a particle of volume Δr² */
  v->rho[iv] = 1.03 * 1000.0;
  const double m_new = 1.03 * m_ref;
  v->mass[iv] = base + 1.0 * m_ref; /* less than m_new: nothing */
  assert_int_equal(sph_open_create_particles(op, sv), 0);
  v->mass[iv] = base + 1.25 * m_new;
  const double m1 = total_mass(sv);
  const size_t n0 = f->n;
  const int64_t id = sv->sys.next_id;
  assert_int_equal(sph_open_create_particles(op, sv), 1);
  f = &sv->sys.part[SPH_KIND_FLUID];
  assert_int_equal(f->n, n0 + 1);
  const size_t a = n0;
  assert_true(f->id[a] == id);
  /* the centre of the entered cell in front of the wall layer: with M(37) (this case) the fitted
   * φΔr, not the lattice's λΔr (numerics.vertex_layer, used with the difference form) */
  assert_true(!sv->cfg.open_gradient_difference && fabs(sv->vertex_phi - 0.5) > 0.05);
  const double off = (sv->vertex_phi + 0.5) * 0.025;
  assert_true(fabs(f->x[0][a] - (0.3 - off)) < 1e-15 && fabs(f->x[1][a] - 0.075) < 1e-15);
  for (int c = 0; c < 3; c++) assert_true(f->v[c][a] == v->v[c][iv]);
  assert_true(f->rho[a] == v->rho[iv] && fabs(f->mass[a] - m_new) <= 1e-15 * m_new);
  assert_true(fabs(v->mass[iv] - (base + 0.25 * m_new)) <= 1e-15 * (base + m_ref));
  assert_true(fabs(total_mass(sv) - m1) <= 1e-15 * m1);
  assert_int_equal(op->created[0], 1);
  /* a second call: 0.25 m_new left, nothing */
  assert_int_equal(sph_open_create_particles(op, sv), 0);
  v->mass[iv] = base; /* back to the wall mass */
  sph_solver_sync(sv);
  /* deletion: the new particle moved behind the segment between (0.3, 0.075) and (0.3, 0.1) */
  f->x[0][a] = 0.305;
  f->x[1][a] = 0.0875;
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  assert_true(sv->nb.behind[a]);
  const double mv = v->mass[iv], mu = v->mass[iu], m2 = total_mass(sv), f_mass = f->mass[a];
  assert_int_equal(sph_open_delete_particles(op, sv), 1);
  f = &sv->sys.part[SPH_KIND_FLUID];
  assert_int_equal(f->n, n0);
  for (size_t b = 0; b < f->n; b++) assert_true(f->id[b] != id);
  assert_true(v->mass[iv] == mv + 0.5 * f_mass && v->mass[iu] == mu + 0.5 * f_mass);
  assert_true(fabs(total_mass(sv) - m2) <= 1e-15 * m2);
  assert_int_equal(op->deleted[0], 1);
  assert_true(op->mass_released[0] == 0.0); /* inflow vertices: J(14), nothing released */
  print_message(
      "created at (%.6g, %.6g) (phi = %.4g) and deleted, total mass unchanged (1e-15); started at "
      "%.15g kg\n",
      0.3 - off, 0.075, sv->vertex_phi, m_start);
  /* at outflow vertices (ṁ < 0): a particle crossing a quarter of the way from (0.3, 0.075) to
   * (0.3, 0.1) brings the first 3/4 and the second 1/4 of the way back to their wall masses; the
   * rest of its mass is released */
  const size_t b0 = 0, nb0 = f->n;
  const int64_t gone = f->id[b0];
  f->x[0][b0] = 0.305;
  f->x[1][b0] = 0.08125;
  sph_solver_sync(sv);
  sph_solver_evaluate(sv);
  assert_true(sv->nb.behind[b0]);
  v->mass[iv] = base - 0.6 * m_ref;
  v->mass[iu] = v->wall_mass[iu] - 0.2 * m_ref;
  op->mdot[iv] = op->mdot[iu] = -1.0;
  const double mv0 = v->mass[iv], mu0 = v->mass[iu], mb = f->mass[b0], m3 = total_mass(sv);
  assert_int_equal(sph_open_delete_particles(op, sv), 1);
  f = &sv->sys.part[SPH_KIND_FLUID];
  assert_int_equal(f->n, nb0 - 1);
  for (size_t b = 0; b < f->n; b++) assert_true(f->id[b] != gone);
  const double dv = 0.75 * (base - mv0), du = 0.25 * (v->wall_mass[iu] - mu0);
  assert_true(fabs(v->mass[iv] - (mv0 + dv)) <= 1e-15 * base &&
              fabs(v->mass[iu] - (mu0 + du)) <= 1e-15 * base);
  assert_true(fabs(op->mass_released[0] - (mb - dv - du)) <= 1e-15 * mb);
  assert_true(fabs(total_mass(sv) + op->mass_released[0] - m3) <= 1e-15 * m3);
  print_message(
      "deleted at outflow vertices 0.6 and 0.2 particle masses below their wall mass "
      "(weights 3/4, 1/4): back by 0.45 and 0.05, %.4g of the particle's mass released\n",
      op->mass_released[0] / mb);
  fixture_solver_destroy(sv);
}

/* The inflow vertices' entered mass as a layer (sph_open_layer, docs/sph-solver.md §10): a vertex
 * 0.4 particle masses above its wall mass puts δm/ρ_v at r_v + (φ + 0.2)Δr n_v (at one particle
 * mass: where the particle will be created), the corner and the wall vertices nothing; in the
 * pressure gradient of a particle near it, that volume counts there instead of at r_v, by hand. */
static void test_layer_hand(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *sv = box_solver("impose: velocity, normal_velocity: 0.05");
  struct sph_open *op = sv->open;
  sph_solver_evaluate(sv);
  struct sph_parts *v = &sv->sys.part[SPH_KIND_VERTEX];
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  size_t iv = (size_t)-1;
  for (size_t i = 0; i < v->n; i++)
    if (fabs(v->x[0][i] - 0.3) < 1e-12 && fabs(v->x[1][i] - 0.075) < 1e-12) iv = i;
  assert_true(iv != (size_t)-1 && v->v[0][iv] < 0.0); /* inflow: into the fluid, −x */
  const double m_new = v->rho[iv] * op->cell_volume, phi = sv->vertex_phi, dr = 0.025;
  v->mass[iv] = v->wall_mass[iv] + 0.4 * m_new;
  sph_open_layer(op, sv);
  const double lv = op->layer_vol[iv];
  assert_true(fabs(lv - 0.4 * m_new / v->rho[iv]) <= 1e-15 * m_new / v->rho[iv]);
  assert_true(fabs(op->layer_x[0][iv] - (0.3 - (phi + 0.2) * dr)) <= 1e-15 &&
              fabs(op->layer_x[1][iv] - 0.075) <= 1e-15);
  size_t nlayer = 0;
  for (size_t i = 0; i < v->n; i++) nlayer += op->layer_vol[i] != 0.0;
  assert_int_equal(nlayer, 1); /* the others are at their wall mass, corners and walls too */
  /* at one particle mass the layer's centre is the created particle's position */
  v->mass[iv] = v->wall_mass[iv] + m_new;
  sph_open_layer(op, sv);
  assert_true(fabs(op->layer_x[0][iv] - (0.3 - (phi + 0.5) * dr)) <= 1e-15);
  v->mass[iv] = v->wall_mass[iv] + 0.4 * m_new;
  sph_open_layer(op, sv);
  /* the particle nearest to the layer's centre: its gradient with and without the layer */
  size_t a = 0;
  double best = INFINITY;
  for (size_t b = 0; b < f->n; b++) {
    const double d = hypot(f->x[0][b] - op->layer_x[0][iv], f->x[1][b] - op->layer_x[1][iv]);
    if (d < best) best = d, a = b;
  }
  const struct sph_op o = {&sv->sys, &sv->kernel, &sv->nb, 0};
  const struct sph_vertex_layer layer = {op->layer_vol, (const double *const *)op->layer_x};
  const double *pk[SPH_NKINDS] = {sv->sys.part[0].p, sv->sys.part[1].p, sv->sys.part[2].p};
  double g1[3], g0[3];
  sph_op_grad_pressure(&o, sv->cfg.grad_k, pk, a, NULL, 0, &layer, g1);
  sph_op_grad_pressure(&o, sv->cfg.grad_k, pk, a, NULL, 0, NULL, g0);
  /* by hand: lv (ratio p_v + p_a / ratio) [∇w(r_a − x_l) − ∇w(r_a − r_v)] / γ_a, k = 1 */
  assert_true(sv->cfg.grad_k == 1.0);
  const double ratio = f->rho[a] / v->rho[iv], sum = ratio * v->p[iv] + f->p[a] / ratio;
  double expect[2];
  for (int c = 0; c < 2; c++) {
    const double dl[2] = {f->x[0][a] - op->layer_x[0][iv], f->x[1][a] - op->layer_x[1][iv]};
    const double dv[2] = {f->x[0][a] - v->x[0][iv], f->x[1][a] - v->x[1][iv]};
    const double rl = hypot(dl[0], dl[1]), rv = hypot(dv[0], dv[1]);
    const double gl = rl < 2.0 * sv->sys.h ? sph_kernel_dwdr_inline(&sv->kernel, rl) / rl : 0.0;
    const double gv = rv < 2.0 * sv->sys.h ? sph_kernel_dwdr_inline(&sv->kernel, rv) / rv : 0.0;
    expect[c] = lv * sum * (gl * dl[c] - gv * dv[c]) / f->gamma[a];
  }
  const double scale = fabs(expect[0]) + fabs(expect[1]);
  print_message(
      "layer: vertex 0.4 particle masses above its wall mass, its layer %.4g m in front; "
      "particle %.3g m from it: gradient change (%.6g, %.6g) Pa/m, by hand (%.6g, %.6g)\n",
      (phi + 0.2) * dr, best, g1[0] - g0[0], g1[1] - g0[1], expect[0], expect[1]);
  assert_true(scale > 0.0);
  for (int c = 0; c < 2; c++) assert_true(fabs(g1[c] - g0[c] - expect[c]) <= 1e-10 * scale);
  fixture_solver_destroy(sv);
}

/* A box open at both ends with a flow at 0.5 m/s through it, no gravity. */
static const char through_case[] = FIXTURE_THROUGH_CASE;

/* A flow at 0.5 m/s through a box open at both ends, with the i/o terms of J(11): particles are
 * created at the inlet and deleted at the outlet, the count adds up, mass is conserved to
 * round-off, and the flow stays uniform over several transits (docs/sph-solver.md §10: the
 * leaving particles, the corner shares of the flux, the wall vertices in the virtual motion). */
static void test_through_flow(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *sv = fixture_solver_from_case(through_case);
  const size_t n0 = sv->sys.part[SPH_KIND_FLUID].n;
  double in;
  print_message("through flow at 0.5 m/s:\n");
  const double err = conservation(sv, 1.2, &in); /* 1.5 transits of the 0.4 m box */
  const struct sph_open *op = sv->open;
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const size_t n1 = f->n;
  double row[SPH_OPEN_CSV_COLUMNS];
  sph_open_csv_row(op, 1, sv->time, row);
  assert_string_equal(sph_open_csv_columns()[14], "deleted");
  assert_string_equal(sph_open_csv_columns()[15], "mass_entered");
  assert_string_equal(sph_open_csv_columns()[16], "mass_released");
  assert_true(row[13] == (double)op->created[1] && row[14] == (double)op->deleted[1] &&
              row[15] == op->mass_entered[1] && row[16] == op->mass_released[1]);
  double du = 0.0, dv = 0.0, drho = 0.0;
  for (size_t a = 0; a < n1; a++) {
    du = fmax(du, fabs(f->v[0][a] - 0.5));
    dv = fmax(dv, fabs(f->v[1][a]));
    drho = fmax(drho, fabs(f->rho[a] / 1000.0 - 1.0));
  }
  print_message(
      "  fluid particles %zu -> %zu; created %ld at the inlet, %ld at the outlet; deleted "
      "%ld at the inlet, %ld at the outlet; at t = %g s: max |u - 0.5| %.3g m/s, max |v| %.3g "
      "m/s, max |rho/rho0 - 1| %.3g; inflow %.9g kg/s, outflow %.9g kg/s\n",
      n0, n1, op->created[0], op->created[1], op->deleted[0], op->deleted[1], sv->time, du, dv,
      drho, op->stats[0].mass_flux, op->stats[1].mass_flux);
  assert_true(err <= 1e-13);
  assert_true(op->created[0] > 11 * 16 && op->deleted[1] > 11 * 16);
  assert_true(op->created[1] == 0 && op->deleted[0] == 0); /* no particle churns at the outlet */
  assert_true((long)n1 ==
              (long)n0 + op->created[0] + op->created[1] - op->deleted[0] - op->deleted[1]);
  assert_true(du <= 1e-3 && dv <= 1e-3 && drho <= 1e-5); /* 0.2 % of the speed */
  /* the inflow ρ0 u over the 11 rows of fluid (11 Δr), not the face's 12 Δr */
  assert_true(fabs(op->stats[0].mass_flux - 1000.0 * 0.5 * 11 * 0.025) <= 1e-4 * 137.5);
  fixture_solver_destroy(sv);
}

/* The through flow stopped by a checkpoint after 130 steps (particles created and deleted by
 * then) and continued to 200 steps, against the same 200 steps in one go: the stores (created and
 * deleted particles included), the vertex masses, the counts and the mass ledgers agree bitwise. */
static void test_restart_through_flow(void **state) {
  (void)state;
  sabre_fp_traps_on();
  struct sph_solver *a = fixture_solver_from_case(through_case),
                    *b = fixture_solver_from_case(through_case);
  enum { total = 200, at = 130 }; /* steps in all, and where the checkpoint is written */
  char msg[1024], ck[] = "/tmp/sabre-test-open-ckpt-XXXXXX";
  const int fd = mkstemp(ck);
  assert_true(fd >= 0);
  close(fd);
  for (int n = 0; n < total; n++)
    if (sph_solver_step(a, INFINITY, msg, sizeof msg) != 0) fail_msg("%s", msg);
  for (int n = 0; n < at; n++)
    if (sph_solver_step(b, INFINITY, msg, sizeof msg) != 0) fail_msg("%s", msg);
  const long created_mid = b->open->created[0], deleted_mid = b->open->deleted[1];
  /* the checkpoint holds created and deleted particles and a released mass */
  assert_true(created_mid > 0 && deleted_mid > 0 && b->open->mass_released[1] != 0.0);
  struct sph_run_counters rc = {.next_output = 1.0};
  assert_int_equal(sph_checkpoint_write(b, &rc, ck), 0);
  fixture_solver_destroy(b);
  b = fixture_solver_from_case(through_case);
  assert_int_equal(sph_checkpoint_read(b, &rc, ck, msg, sizeof msg), 0);
  free(rc.output_times);
  unlink(ck);
  assert_int_equal(b->open->created[0], created_mid);
  for (int n = at; n < total; n++)
    if (sph_solver_step(b, INFINITY, msg, sizeof msg) != 0) fail_msg("%s", msg);
  const struct sph_parts *fa = &a->sys.part[SPH_KIND_FLUID], *fb = &b->sys.part[SPH_KIND_FLUID];
  const struct sph_parts *va = &a->sys.part[SPH_KIND_VERTEX], *vb = &b->sys.part[SPH_KIND_VERTEX];
  print_message(
      "checkpoint at step %d (created %ld, deleted %ld), step %d: created %ld, deleted "
      "%ld, %zu fluid particles\n",
      at, created_mid, deleted_mid, total, a->open->created[0], a->open->deleted[1], fa->n);
  assert_true(a->open->created[0] > created_mid && a->open->deleted[1] > deleted_mid);
  assert_int_equal(fa->n, fb->n);
  assert_memory_equal(fa->id, fb->id, fa->n * sizeof *fa->id);
  assert_memory_equal(fa->rho, fb->rho, fa->n * sizeof(double));
  assert_memory_equal(fa->mass, fb->mass, fa->n * sizeof(double));
  for (int c = 0; c < 2; c++) {
    assert_memory_equal(fa->x[c], fb->x[c], fa->n * sizeof(double));
    assert_memory_equal(fa->v[c], fb->v[c], fa->n * sizeof(double));
  }
  assert_memory_equal(va->mass, vb->mass, va->n * sizeof(double));
  for (int g = 0; g < 2; g++) {
    assert_int_equal(a->open->created[g], b->open->created[g]);
    assert_int_equal(a->open->deleted[g], b->open->deleted[g]);
    assert_true(a->open->mass_entered[g] == b->open->mass_entered[g] &&
                a->open->mass_released[g] == b->open->mass_released[g] &&
                a->open->mass_withheld[g] == b->open->mass_withheld[g]);
  }
  assert_true(a->time == b->time && a->sys.next_id == b->sys.next_id);
  fixture_solver_destroy(a);
  fixture_solver_destroy(b);
}

/* A 1D pipe 2 m long at a uniform 10 kPa with a flow of 0.2 m/s (velocity inlet, outlet at
 * 10 kPa, c0 = 20 m/s): the flow must stay uniform whatever the pressure level. With M(37) as
 * it is (numerics.open_gradient: symmetric) the zeroth-order defect of the rows flowing past the
 * open boundaries pushes in proportion to the level: the mean speed is 28 % off within a second
 * and particles accumulate; with the difference form next to the open boundaries
 * (docs/sph-solver.md §10) the mean speed and pressure hold (measured: within 1.4 % and 0.45 %). */
static const char level_case[] =
    "geometry:\n"
    "  dimension: 1\n"
    "  dr: 0.025\n"
    "  first_row: 1\n"
    "  walls: [{type: interval, lo: [0], hi: [2], open: [x-, x+]}]\n"
    "  fluid: [{type: box, lo: [0], hi: [2]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "initial: {pressure: '10000', velocity: ['0.2']}\n"
    "numerics: {open_gradient: %s}\n"
    "time: {end: 1}\n"
    "open_boundaries:\n"
    "  - {name: in, wall: 0, edges: [1], impose: velocity, normal_velocity: 0.2}\n"
    "  - {name: out, wall: 0, edges: [2], impose: pressure, pressure: 10000}\n";

/* The largest deviations of the mean speed (relative to 0.2 m/s) and mean pressure (relative to
 * 10 kPa) at t = 0.25, 0.5, 0.75, 1 s, and of the particle count from the start. */
static void level_run(const char *form, double *du, double *dp, long *dn) {
  char text[sizeof level_case + 32];
  snprintf(text, sizeof text, level_case, form);
  struct sph_solver *sv = fixture_solver_from_case(text);
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  const long n0 = (long)f->n;
  char msg[1024];
  *du = *dp = 0.0;
  *dn = 0;
  for (int k = 1; k <= 4; k++) {
    while (sv->time < 0.25 * k - 1e-12)
      if (sph_solver_step(sv, 0.25 * k - sv->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
    double u = 0.0, p = 0.0;
    for (size_t a = 0; a < f->n; a++) u += f->v[0][a], p += f->p[a];
    u /= (double)f->n;
    p /= (double)f->n;
    *du = fmax(*du, fabs(u / 0.2 - 1.0));
    *dp = fmax(*dp, fabs(p / 1e4 - 1.0));
    *dn = labs((long)f->n - n0) > *dn ? labs((long)f->n - n0) : *dn;
  }
  print_message("  %-10s mean u within %.3g, mean p within %.3g, particle count within %ld\n", form,
                *du, *dp, *dn);
  fixture_solver_destroy(sv);
}

static void test_pressure_level(void **state) {
  (void)state;
  sabre_fp_traps_on();
  print_message("uniform flow at 0.2 m/s and 10 kPa through a 1D pipe, to t = 1 s:\n");
  double du, dp;
  long dn;
  level_run("difference", &du, &dp, &dn);
  /* measured 2.2e-4 and 2.7e-4; 1.4 % and 0.45 % while the difference form's new rows were
   * created at (φ + 1/2)Δr, not on the lattice (docs/sph-solver.md §10) */
  assert_true(du <= 1e-3 && dp <= 5e-4 && dn <= 1);
  level_run("symmetric", &du, &dp, &dn); /* the defect this form leaves: the test can fail */
  assert_true(du > 0.05);
}

/* The valve end of cases/compare/water_hammer_2d at Δr = 1.25 mm: a channel 0.1 m × 0.02 m between
 * free-slip walls at rest at 4 kPa, closed at x = 0, u = 0 imposed on the open face at x = 0.1 m,
 * the hammer's numerics (Brezzi diffusion, no_pull: normal, wall_vertex_mass: density, 300
 * repacking steps), to 0.03 s. With M(37) (symmetric) the fluid stays at rest (measured
 * 0.0065 m/s); the difference form next to a velocity face at a pressure level is unstable in 2D
 * (docs/sph-solver.md §10, "Still open" and "Tried next (2026-12-08)"): the particles next to
 * the face's corners move across, measured
 * 0.062 m/s by 0.03 s (0.17 by 0.06 s; at Δr = 0.625 mm 0.44 m/s by 0.07 s and the hammer
 * stops). The second assertion records that defect: it fails once the form is fixed. */
static const char valve_case[] =
    "geometry:\n"
    "  dimension: 2\n"
    "  dr: 0.00125\n"
    "  first_row: 1\n"
    "  walls: [{type: box, lo: [0, 0], hi: [0.1, 0.02], open: [x+]}]\n"
    "  fluid: [{type: box, lo: [0, 0], hi: [0.1, 0.02]}]\n"
    "fluid: {rho0: 1000, c0: 20}\n"
    "initial: {pressure: '4000'}\n"
    "numerics: {diffusion: brezzi, open_gradient: %s, no_pull: normal,\n"
    "           wall_vertex_mass: density}\n"
    "repack: {steps: 300}\n"
    "time: {end: 1}\n"
    "open_boundaries:\n"
    "  - {name: valve, wall: 0, faces: [x+], impose: velocity, normal_velocity: 0}\n";

/* The largest |v_y| of the valve end over 0.03 s with the given form. */
static double valve_run(const char *form) {
  char text[sizeof valve_case + 32];
  snprintf(text, sizeof text, valve_case, form);
  struct sph_solver *sv = fixture_solver_from_case(text);
  const struct sph_parts *f = &sv->sys.part[SPH_KIND_FLUID];
  char msg[1024];
  double vmax = 0.0;
  while (sv->time < 0.03 - 1e-12) {
    if (sph_solver_step(sv, 0.03 - sv->time, msg, sizeof msg) != 0) fail_msg("%s", msg);
    for (size_t a = 0; a < f->n; a++) vmax = fmax(vmax, fabs(f->v[1][a]));
  }
  print_message("  %-10s %zu particles, to 0.03 s: largest |v_y| %.4f m/s\n", form, f->n, vmax);
  fixture_solver_destroy(sv);
  return vmax;
}

static void test_valve_corner(void **state) {
  (void)state;
  print_message("valve end at 4 kPa:\n");
  assert_true(valve_run("symmetric") <= 0.02);
  assert_true(valve_run("difference") > 0.04); /* the known defect (above) */
}

/* The mass ledgers' compensated sum: 10⁶ steps of 0.005–0.015 kg (pseudo-random) onto a total that
 * grows to 10⁴ kg (a long run's entered mass) stay within two units in the last place of a
 * reference summed in long double with the same compensation, where the plain sum drifts by
 * hundreds of them. */
static void test_ledger_sum(void **state) {
  (void)state;
  double sum = 0.0, comp = 0.0, plain = 0.0;
  long double ref = 0.0L, refc = 0.0L;
  unsigned rng = 2024u;
  for (long i = 0; i < 1000000; i++) {
    rng = rng * 1664525u + 1013904223u;
    const double x = 0.005 + 0.01 * ((double)(rng >> 8) / (double)(1u << 24));
    sph_open_kahan_add(&sum, &comp, x);
    plain += x;
    const long double y = (long double)x - refc, t = ref + y;
    refc = (t - ref) - y;
    ref = t;
  }
  const double ulp = nextafter(sum, INFINITY) - sum;
  const double err = fabs((double)((long double)sum - ref)),
               err_plain = fabs((double)((long double)plain - ref));
  print_message("ledger of 1e6 steps: %.6f kg; compensated error %.2g ulp, plain %.2g ulp\n", sum,
                err / ulp, err_plain / ulp);
  assert_true(err <= 2.0 * ulp);
  assert_true(err_plain >= 100.0 * ulp); /* the case the compensation is there for */
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_vertex_mass_hand),     cmocka_unit_test(test_conservation),
      cmocka_unit_test(test_layer_hand),           cmocka_unit_test(test_io_terms),
      cmocka_unit_test(test_create_delete_hand),   cmocka_unit_test(test_through_flow),
      cmocka_unit_test(test_restart_through_flow), cmocka_unit_test(test_pressure_level),
      cmocka_unit_test(test_outflow_floor),        cmocka_unit_test(test_ledger_sum),
      cmocka_unit_test(test_valve_corner),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
