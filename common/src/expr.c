/* Expressions of x for initial profiles, compiled once by recursive descent into a small postfix
 * program and evaluated per quadrature point:
 *   expr := term (('+'|'-') term)*      term := unary (('*'|'/') unary)*
 *   unary := '-' unary | '+' unary | power     power := atom ('^' unary)?
 *   atom := number | 'x' | 'pi' | name '(' expr ')' | '(' expr ')'                            */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

enum op { OP_NUM, OP_X, OP_ADD, OP_SUB, OP_MUL, OP_DIV, OP_POW, OP_NEG, OP_FUN };

typedef double (*fun1)(double);
static const struct {
  const char *name;
  fun1 f;
} functions[] = {{"sin", sin},   {"cos", cos},  {"tan", tan},   {"exp", exp},   {"log", log},
                 {"sqrt", sqrt}, {"abs", fabs}, {"tanh", tanh}, {"cosh", cosh}, {"sinh", sinh}};

struct instr {
  enum op op;
  double value;
  fun1 f;
};

struct fv1d_expr {
  struct instr *code;
  size_t len, cap;
  int depth; /* stack depth needed */
};

struct parser {
  const char *text, *pos;
  struct fv1d_expr *e;
  char *err;
  size_t errlen;
  int failed;
};

static void emit(struct parser *ps, enum op op, double value, fun1 f) {
  struct fv1d_expr *e = ps->e;
  if (e->len == e->cap) {
    e->cap = e->cap ? 2 * e->cap : 16;
    e->code = cmn_realloc(e->code, e->cap * sizeof *e->code);
  }
  e->code[e->len++] = (struct instr){op, value, f};
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
    emit(ps, OP_NUM, v, NULL);
    return;
  }
  if (isalpha((unsigned char)*p)) {
    const char *q = p;
    while (isalnum((unsigned char)*q) || *q == '_') ++q;
    size_t n = (size_t)(q - p);
    ps->pos = q;
    if (n == 1 && *p == 'x') return emit(ps, OP_X, 0.0, NULL);
    if (n == 2 && strncmp(p, "pi", 2) == 0) return emit(ps, OP_NUM, 3.14159265358979323846, NULL);
    for (size_t k = 0; k < sizeof functions / sizeof functions[0]; ++k) {
      if (strlen(functions[k].name) == n && strncmp(p, functions[k].name, n) == 0) {
        skip(ps);
        if (*ps->pos != '(') return fail(ps, "expected '(' after a function name");
        ++ps->pos;
        parse_expr(ps);
        skip(ps);
        if (*ps->pos != ')') return fail(ps, "expected ')'");
        ++ps->pos;
        return emit(ps, OP_FUN, 0.0, functions[k].f);
      }
    }
    ps->pos = p;
    return fail(ps,
                "unknown name (variables: x, pi; functions: sin cos tan exp log sqrt abs "
                "tanh cosh sinh)");
  }
  fail(ps, *p ? "unexpected character" : "unexpected end");
}

static void parse_power(struct parser *ps) {
  parse_atom(ps);
  skip(ps);
  if (*ps->pos == '^') {
    ++ps->pos;
    parse_unary(ps); /* right associative: 2^-x, 2^3^2 = 2^9 */
    emit(ps, OP_POW, 0.0, NULL);
  }
}

static void parse_unary(struct parser *ps) {
  skip(ps);
  if (*ps->pos == '-') {
    ++ps->pos;
    parse_unary(ps);
    emit(ps, OP_NEG, 0.0, NULL);
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
    emit(ps, c == '*' ? OP_MUL : OP_DIV, 0.0, NULL);
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
    emit(ps, c == '+' ? OP_ADD : OP_SUB, 0.0, NULL);
  }
}

struct fv1d_expr *fv1d_expr_compile(const char *text, char *err, size_t errlen) {
  struct fv1d_expr *e = cmn_calloc(1, sizeof *e);
  struct parser ps = {text, text, e, err, errlen, 0};
  parse_expr(&ps);
  skip(&ps);
  if (!ps.failed && *ps.pos) fail(&ps, "unexpected character");
  int depth = 0;
  for (size_t k = 0; k < e->len && !ps.failed; ++k) {
    switch (e->code[k].op) {
      case OP_NUM:
      case OP_X:
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
    fv1d_expr_free(e);
    return NULL;
  }
  return e;
}

double fv1d_expr_eval(const struct fv1d_expr *e, double x) {
  double stack_small[32] = {0.0};
  double *st = e->depth <= 32 ? stack_small : cmn_malloc((size_t)e->depth * sizeof(double));
  int top = 0;
  for (size_t k = 0; k < e->len; ++k) {
    const struct instr *in = &e->code[k];
    switch (in->op) {
      case OP_NUM:
        st[top++] = in->value;
        break;
      case OP_X:
        st[top++] = x;
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

void fv1d_expr_free(struct fv1d_expr *e) {
  if (!e) return;
  free(e->code);
  free(e);
}
