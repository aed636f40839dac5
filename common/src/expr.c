/* Expressions of named variables for initial profiles (common.h, docs/case-files.md), compiled
 * once by recursive descent into a small postfix program and evaluated per point:
 *   expr := term (('+'|'-') term)*      term := unary (('*'|'/') unary)*
 *   unary := '-' unary | '+' unary | power     power := atom ('^' unary)?
 *   atom := number | variable | 'pi' | function '(' expr ')' | '(' expr ')'                   */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sabre/common.h"

enum op { OP_NUM, OP_VAR, OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_POW, OP_NEG, OP_FUN };

typedef double (*fun1)(double);
static const struct {
  const char *name;
  fun1 f;
} functions[] = {{"sin", sin},   {"cos", cos},   {"tan", tan},  {"asin", asin}, {"acos", acos},
                 {"atan", atan}, {"exp", exp},   {"log", log},  {"sqrt", sqrt}, {"abs", fabs},
                 {"tanh", tanh}, {"cosh", cosh}, {"sinh", sinh}};

struct instr {
  enum op op;
  double value; /* OP_NUM */
  int var;      /* OP_VAR: index into the variable values */
  fun1 f;       /* OP_FUN */
};

struct cmn_expr {
  struct instr *code;
  size_t len, cap;
  int depth; /* stack depth needed */
};

struct parser {
  const char *text, *pos;
  int nvars;
  const char *const *vars;
  struct cmn_expr *e;
  char *err;
  size_t errlen;
  int failed;
};

static void emit(struct parser *ps, enum op op, double value, int var, fun1 f) {
  struct cmn_expr *e = ps->e;
  if (e->len == e->cap) {
    e->cap = e->cap ? 2 * e->cap : 16;
    e->code = cmn_realloc(e->code, e->cap * sizeof *e->code);
  }
  e->code[e->len++] = (struct instr){op, value, var, f};
}

static void fail(struct parser *ps, const char *what) {
  if (!ps->failed)
    snprintf(ps->err, ps->errlen, "expression '%s': %s at column %d", ps->text, what,
             (int)(ps->pos - ps->text) + 1);
  ps->failed = 1;
}

static void skip(struct parser *ps) {
  while (isspace((unsigned char)*ps->pos)) ++ps->pos;
}

static void parse_expr(struct parser *ps);
static void parse_unary(struct parser *ps);

static void parse_atom(struct parser *ps) {
  skip(ps);
  const char *p = ps->pos;
  if (*p == '(') {
    ++ps->pos;
    parse_expr(ps);
    skip(ps);
    if (*ps->pos != ')') return fail(ps, "expected ')'");
    ++ps->pos;
    return;
  }
  if (isdigit((unsigned char)*p) || *p == '.') {
    char *end;
    double v = strtod(p, &end);
    if (end == p) return fail(ps, "bad number");
    ps->pos = end;
    emit(ps, OP_NUM, v, 0, NULL);
    return;
  }
  if (isalpha((unsigned char)*p)) {
    const char *q = p;
    while (isalnum((unsigned char)*q) || *q == '_') ++q;
    size_t n = (size_t)(q - p);
    ps->pos = q;
    for (int k = 0; k < ps->nvars; ++k)
      if (strlen(ps->vars[k]) == n && strncmp(p, ps->vars[k], n) == 0)
        return emit(ps, OP_VAR, 0.0, k, NULL);
    if (n == 2 && strncmp(p, "pi", 2) == 0)
      return emit(ps, OP_NUM, 3.14159265358979323846, 0, NULL);
    for (size_t k = 0; k < sizeof functions / sizeof functions[0]; ++k) {
      if (strlen(functions[k].name) == n && strncmp(p, functions[k].name, n) == 0) {
        skip(ps);
        if (*ps->pos != '(') return fail(ps, "expected '(' after a function name");
        ++ps->pos;
        parse_expr(ps);
        skip(ps);
        if (*ps->pos != ')') return fail(ps, "expected ')'");
        ++ps->pos;
        return emit(ps, OP_FUN, 0.0, 0, functions[k].f);
      }
    }
    ps->pos = p;
    char what[512];
    size_t len = (size_t)snprintf(what, sizeof what, "unknown name '%.*s' (variables:", (int)n, p);
    for (int k = 0; k < ps->nvars && len < sizeof what; ++k)
      len += (size_t)snprintf(what + len, sizeof what - len, " %s,", ps->vars[k]);
    if (len < sizeof what)
      snprintf(what + len, sizeof what - len,
               " pi; functions: sin cos tan asin acos atan exp log sqrt abs tanh cosh sinh)");
    return fail(ps, what);
  }
  fail(ps, *p ? "unexpected character" : "unexpected end");
}

static void parse_power(struct parser *ps) {
  parse_atom(ps);
  skip(ps);
  if (*ps->pos == '^') {
    ++ps->pos;
    parse_unary(ps); /* right associative: 2^-x, 2^3^2 = 2^9 */
    emit(ps, OP_POW, 0.0, 0, NULL);
  }
}

static void parse_unary(struct parser *ps) {
  skip(ps);
  if (*ps->pos == '-') {
    ++ps->pos;
    parse_unary(ps);
    emit(ps, OP_NEG, 0.0, 0, NULL);
  } else if (*ps->pos == '+') {
    ++ps->pos;
    parse_unary(ps);
  } else {
    parse_power(ps);
  }
}

static void parse_term(struct parser *ps) {
  parse_unary(ps);
  for (;;) {
    skip(ps);
    char c = *ps->pos;
    if (c != '*' && c != '/') return;
    ++ps->pos;
    parse_unary(ps);
    emit(ps, c == '*' ? OP_MUL : OP_DIV, 0.0, 0, NULL);
  }
}

static void parse_expr(struct parser *ps) {
  if (ps->failed) return;
  parse_term(ps);
  for (;;) {
    skip(ps);
    char c = *ps->pos;
    if (c != '+' && c != '-') return;
    ++ps->pos;
    parse_term(ps);
    emit(ps, c == '+' ? OP_ADD : OP_SUB, 0.0, 0, NULL);
  }
}

struct cmn_expr *cmn_expr_compile(const char *text, int nvars, const char *const *vars, char *err,
                                  size_t errlen) {
  struct cmn_expr *e = cmn_calloc(1, sizeof *e);
  char scratch[8];
  if (!err || errlen == 0) err = scratch, errlen = sizeof scratch;
  struct parser ps = {text, text, nvars, vars, e, err, errlen, 0};
  parse_expr(&ps);
  skip(&ps);
  if (!ps.failed && *ps.pos) fail(&ps, "unexpected character");
  int depth = 0;
  for (size_t k = 0; k < e->len && !ps.failed; ++k) {
    switch (e->code[k].op) {
      case OP_NUM:
      case OP_VAR:
        ++depth;
        break;
      case OP_NEG:
      case OP_FUN:
        break;
      default:
        --depth;
        break;
    }
    if (depth > e->depth) e->depth = depth;
  }
  if (ps.failed) {
    cmn_expr_free(e);
    return NULL;
  }
  return e;
}

double cmn_expr_eval(const struct cmn_expr *e, const double *vals) {
  double stack_small[32] = {0.0};
  double *st = e->depth <= 32 ? stack_small : cmn_malloc((size_t)e->depth * sizeof(double));
  int top = 0;
  for (size_t k = 0; k < e->len; ++k) {
    const struct instr *in = &e->code[k];
    switch (in->op) {
      case OP_NUM:
        st[top++] = in->value;
        break;
      case OP_VAR:
        st[top++] = vals[in->var];
        break;
      case OP_NEG:
        st[top - 1] = -st[top - 1];
        break;
      case OP_FUN:
        st[top - 1] = in->f(st[top - 1]);
        break;
      case OP_ADD:
        --top;
        st[top - 1] += st[top];
        break;
      case OP_SUB:
        --top;
        st[top - 1] -= st[top];
        break;
      case OP_MUL:
        --top;
        st[top - 1] *= st[top];
        break;
      case OP_DIV:
        --top;
        st[top - 1] /= st[top];
        break;
      case OP_POW:
        --top;
        st[top - 1] = pow(st[top - 1], st[top]);
        break;
    }
  }
  double v = st[0];
  if (st != stack_small) free(st);
  return v;
}

void cmn_expr_free(struct cmn_expr *e) {
  if (!e) return;
  free(e->code);
  free(e);
}
