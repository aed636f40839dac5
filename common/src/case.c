/* Case files: YAML read through libyaml's event parser into a small tree of nodes, typed getters
 * by path, defaults written back into the tree, `--set` overrides, an unused-key check and the
 * writer for used_case.yaml.
 *
 * Every node keeps where it came from: a (line, column) in the file, or the `--set` assignment
 * that created it, or nothing for an inserted default. Messages name that origin so that the user
 * can find the offending text. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <yaml.h>

#include "sabre/common.h"

enum node_kind { NODE_SCALAR, NODE_SEQ, NODE_MAP };

struct cmn_node {
  enum node_kind kind;
  int line, col;      /**< 1-based position of the value in the file, 0 if none */
  int used;           /**< read by a getter (containers: read as a whole or as a section) */
  int quoted;         /**< scalar written in quotes: a string, never null */
  const char *origin; /**< the --set assignment that created the node, or NULL */
  char *value;        /**< scalar text */
  /* Set when the node is a mapping value. */
  char *key;
  int key_line, key_col;
  /* Children of a sequence or mapping, in document order. */
  struct cmn_node **items;
  int n, cap;
};

struct cmn_case {
  char *name;
  struct cmn_node *root;
  int fatal;
  char err[4096];
  /* The --set assignments, kept alive because nodes point to them. */
  char **sets;
  int nsets;
};

/* Deepest allowed nesting; far beyond any sensible case file, and keeps the recursion bounded. */
#define MAX_DEPTH 64

/* ---------------------------------------------------------------------------------------------
 * Nodes
 * ------------------------------------------------------------------------------------------- */

static char *dup_n(const char *s, size_t n) {
  char *d = cmn_malloc(n + 1);
  memcpy(d, s, n);
  d[n] = '\0';
  return d;
}

static char *dup_s(const char *s) { return dup_n(s, strlen(s)); }

static struct cmn_node *node_new(enum node_kind kind) {
  struct cmn_node *n = cmn_calloc(1, sizeof *n);
  n->kind = kind;
  return n;
}

static struct cmn_node *scalar_new(const char *text, int quoted) {
  struct cmn_node *n = node_new(NODE_SCALAR);
  n->value = dup_s(text);
  n->quoted = quoted;
  return n;
}

static void node_free(struct cmn_node *n) {
  if (n == NULL) return;
  for (int i = 0; i < n->n; ++i) node_free(n->items[i]);
  free(n->items);
  free(n->value);
  free(n->key);
  free(n);
}

static void node_append(struct cmn_node *parent, struct cmn_node *child) {
  if (parent->n == parent->cap) {
    parent->cap = parent->cap > 0 ? 2 * parent->cap : 4;
    parent->items = cmn_realloc(parent->items, (size_t)parent->cap * sizeof *parent->items);
  }
  parent->items[parent->n++] = child;
}

static struct cmn_node *map_find(const struct cmn_node *map, const char *key, size_t keylen) {
  for (int i = 0; i < map->n; ++i) {
    const char *k = map->items[i]->key;
    if (strlen(k) == keylen && memcmp(k, key, keylen) == 0) return map->items[i];
  }
  return NULL;
}

static void mark_tree(struct cmn_node *n) {
  n->used = 1;
  for (int i = 0; i < n->n; ++i) mark_tree(n->items[i]);
}

static void set_origin(struct cmn_node *n, const char *origin) {
  n->origin = origin;
  n->line = n->col = 0;
  for (int i = 0; i < n->n; ++i) {
    set_origin(n->items[i], origin);
    n->items[i]->key_line = n->items[i]->key_col = 0;
  }
}

/* YAML 1.2 core-schema nulls; a quoted scalar is always a string. */
static int is_null(const struct cmn_node *n) {
  if (n->kind != NODE_SCALAR || n->quoted) return 0;
  const char *v = n->value;
  return v[0] == '\0' || strcmp(v, "~") == 0 || strcmp(v, "null") == 0 || strcmp(v, "Null") == 0 ||
         strcmp(v, "NULL") == 0;
}

/* ---------------------------------------------------------------------------------------------
 * Building the tree from libyaml events
 * ------------------------------------------------------------------------------------------- */

struct builder {
  yaml_parser_t parser;
  const char *name;   /**< file name for messages */
  const char *origin; /**< --set assignment, or NULL for a file */
  char *err;
  size_t errlen;
  int failed;
};

static void build_fail(struct builder *b, yaml_mark_t mark, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static void build_fail(struct builder *b, yaml_mark_t mark, const char *fmt, ...) {
  if (b->failed) return;
  b->failed = 1;
  if (b->err == NULL || b->errlen == 0) return;
  char what[1024];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(what, sizeof what, fmt, ap);
  va_end(ap);
  snprintf(b->err, b->errlen, "%s:%lu:%lu: %s", b->name, (unsigned long)mark.line + 1,
           (unsigned long)mark.column + 1, what);
}

static int next_event(struct builder *b, yaml_event_t *ev) {
  if (yaml_parser_parse(&b->parser, ev)) return 0;
  const yaml_parser_t *p = &b->parser;
  const char *problem = p->problem != NULL ? p->problem : "malformed YAML";
  if (p->error == YAML_READER_ERROR) {
    build_fail(b, p->problem_mark, "%s (byte offset %lu)", problem,
               (unsigned long)p->problem_offset);
  } else if (p->context != NULL) {
    build_fail(b, p->problem_mark, "%s (%s at line %lu, column %lu)", problem, p->context,
               (unsigned long)p->context_mark.line + 1, (unsigned long)p->context_mark.column + 1);
  } else {
    build_fail(b, p->problem_mark, "%s", problem);
  }
  return -1;
}

static void place_mark(struct cmn_node *n, const struct builder *b, yaml_mark_t mark) {
  if (b->origin != NULL) {
    n->origin = b->origin;
  } else {
    n->line = (int)mark.line + 1;
    n->col = (int)mark.column + 1;
  }
}

/* Build the node starting with event `ev` (which the caller deletes), consuming the events up to
 * and including its end. NULL on error (message in the builder). */
static struct cmn_node *build_node(struct builder *b, const yaml_event_t *ev, int depth) {
  if (depth > MAX_DEPTH) {
    build_fail(b, ev->start_mark, "nesting deeper than %d levels", MAX_DEPTH);
    return NULL;
  }
  struct cmn_node *node = NULL;
  switch (ev->type) {
    case YAML_SCALAR_EVENT: {
      int quoted = ev->data.scalar.style != YAML_PLAIN_SCALAR_STYLE;
      node = scalar_new((const char *)ev->data.scalar.value, quoted);
      /* A NUL inside the scalar would silently cut it; refuse it. */
      if (strlen(node->value) != ev->data.scalar.length) {
        build_fail(b, ev->start_mark, "scalar contains a NUL character");
        node_free(node);
        return NULL;
      }
      place_mark(node, b, ev->start_mark);
      return node;
    }
    case YAML_ALIAS_EVENT:
      build_fail(b, ev->start_mark, "aliases (*%s) are not supported in case files",
                 (const char *)ev->data.alias.anchor);
      return NULL;
    case YAML_SEQUENCE_START_EVENT: {
      node = node_new(NODE_SEQ);
      place_mark(node, b, ev->start_mark);
      for (;;) {
        yaml_event_t item;
        if (next_event(b, &item) != 0) break;
        if (item.type == YAML_SEQUENCE_END_EVENT) {
          yaml_event_delete(&item);
          return node;
        }
        struct cmn_node *child = build_node(b, &item, depth + 1);
        yaml_event_delete(&item);
        if (child == NULL) break;
        node_append(node, child);
      }
      node_free(node);
      return NULL;
    }
    case YAML_MAPPING_START_EVENT: {
      node = node_new(NODE_MAP);
      place_mark(node, b, ev->start_mark);
      for (;;) {
        yaml_event_t key;
        if (next_event(b, &key) != 0) break;
        if (key.type == YAML_MAPPING_END_EVENT) {
          yaml_event_delete(&key);
          return node;
        }
        if (key.type != YAML_SCALAR_EVENT) {
          build_fail(b, key.start_mark, "mapping keys must be plain names");
          yaml_event_delete(&key);
          break;
        }
        const char *k = (const char *)key.data.scalar.value;
        const struct cmn_node *first = map_find(node, k, strlen(k));
        if (first != NULL) {
          if (first->key_line > 0)
            build_fail(b, key.start_mark, "duplicate key '%s' (first defined at line %d)", k,
                       first->key_line);
          else
            build_fail(b, key.start_mark, "duplicate key '%s'", k);
          yaml_event_delete(&key);
          break;
        }
        if (k[0] == '\0') {
          build_fail(b, key.start_mark, "empty key");
          yaml_event_delete(&key);
          break;
        }
        yaml_event_t value;
        if (next_event(b, &value) != 0) {
          yaml_event_delete(&key);
          break;
        }
        struct cmn_node *child = build_node(b, &value, depth + 1);
        yaml_event_delete(&value);
        if (child == NULL) {
          yaml_event_delete(&key);
          break;
        }
        child->key = dup_s(k);
        if (b->origin == NULL) {
          child->key_line = (int)key.start_mark.line + 1;
          child->key_col = (int)key.start_mark.column + 1;
        }
        yaml_event_delete(&key);
        node_append(node, child);
      }
      node_free(node);
      return NULL;
    }
    default:
      build_fail(b, ev->start_mark, "unexpected YAML event");
      return NULL;
  }
}

/* Parse one YAML document from text. *root is NULL for an empty stream. 0 / -1. */
static int build_document(struct builder *b, const char *text, size_t len, struct cmn_node **root) {
  *root = NULL;
  if (!yaml_parser_initialize(&b->parser)) {
    yaml_mark_t none = {0, 0, 0};
    build_fail(b, none, "cannot initialise the YAML parser");
    return -1;
  }
  yaml_parser_set_input_string(&b->parser, (const unsigned char *)text, len);
  struct cmn_node *doc = NULL;
  int documents = 0;
  for (;;) {
    yaml_event_t ev;
    if (next_event(b, &ev) != 0) break;
    yaml_event_type_t type = ev.type;
    if (type == YAML_DOCUMENT_START_EVENT && ++documents > 1)
      build_fail(b, ev.start_mark, "more than one YAML document ('---'); expected one");
    else if (type == YAML_SCALAR_EVENT || type == YAML_SEQUENCE_START_EVENT ||
             type == YAML_MAPPING_START_EVENT || type == YAML_ALIAS_EVENT)
      doc = build_node(b, &ev, 0);
    yaml_event_delete(&ev);
    if (b->failed || type == YAML_STREAM_END_EVENT) break;
  }
  yaml_parser_delete(&b->parser);
  if (b->failed) {
    node_free(doc);
    return -1;
  }
  *root = doc;
  return 0;
}

struct cmn_case *cmn_case_parse(const char *text, const char *name, char *err, size_t errlen) {
  if (err != NULL && errlen > 0) err[0] = '\0';
  if (name == NULL) name = "<case>";
  struct builder b = {.name = name, .err = err, .errlen = errlen};
  struct cmn_node *root = NULL;
  if (build_document(&b, text != NULL ? text : "", text != NULL ? strlen(text) : 0, &root) != 0)
    return NULL;
  if (root == NULL || root->kind != NODE_MAP) {
    if (err != NULL && errlen > 0) {
      if (root == NULL)
        snprintf(err, errlen, "%s: empty case file; expected a mapping of keys", name);
      else
        snprintf(err, errlen, "%s:%d:%d: expected a mapping of keys at the top level, got a %s",
                 name, root->line, root->col, root->kind == NODE_SEQ ? "sequence" : "scalar");
    }
    node_free(root);
    return NULL;
  }
  struct cmn_case *c = cmn_calloc(1, sizeof *c);
  c->name = dup_s(name);
  c->root = root;
  c->fatal = 1;
  return c;
}

struct cmn_case *cmn_case_load(const char *path, char *err, size_t errlen) {
  if (err != NULL && errlen > 0) err[0] = '\0';
  FILE *f = fopen(path, "rb");
  if (f == NULL) {
    if (err != NULL && errlen > 0)
      snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
    return NULL;
  }
  size_t len = 0, cap = 4096;
  char *text = cmn_malloc(cap);
  for (;;) {
    size_t got = fread(text + len, 1, cap - len - 1, f);
    len += got;
    if (len + 1 < cap) break;
    cap *= 2;
    text = cmn_realloc(text, cap);
  }
  int bad = ferror(f);
  fclose(f);
  if (bad) {
    if (err != NULL && errlen > 0) snprintf(err, errlen, "%s: read error", path);
    free(text);
    return NULL;
  }
  text[len] = '\0';
  if (strlen(text) != len) {
    if (err != NULL && errlen > 0) snprintf(err, errlen, "%s: file contains a NUL byte", path);
    free(text);
    return NULL;
  }
  struct cmn_case *c = cmn_case_parse(text, path, err, errlen);
  free(text);
  return c;
}

void cmn_case_free(struct cmn_case *c) {
  if (c == NULL) return;
  node_free(c->root);
  for (int i = 0; i < c->nsets; ++i) free(c->sets[i]);
  free(c->sets);
  free(c->name);
  free(c);
}

void cmn_case_set_fatal(struct cmn_case *c, int fatal) { c->fatal = fatal != 0; }

const char *cmn_case_error(const struct cmn_case *c) { return c->err; }

const char *cmn_case_name(const struct cmn_case *c) { return c->name; }

/* ---------------------------------------------------------------------------------------------
 * Errors
 * ------------------------------------------------------------------------------------------- */

/* The line a user sees for a node: a section (mapping or sequence) that is the value of a key
 * starts where its key is written; a scalar is where its value is. */
static int node_line(const struct cmn_node *n) {
  return n->kind != NODE_SCALAR && n->key_line > 0 ? n->key_line : n->line;
}

/* Where a node came from: "case.yaml:12:7", "case.yaml (--set a.b=1)" or "case.yaml". */
static void where(const struct cmn_case *c, const struct cmn_node *n, int use_key, char *buf,
                  size_t len) {
  if (n != NULL && n->kind != NODE_SCALAR && n->key_line > 0) use_key = 1;
  int line = n != NULL ? (use_key ? n->key_line : n->line) : 0;
  int col = n != NULL ? (use_key ? n->key_col : n->col) : 0;
  if (n != NULL && n->origin != NULL)
    snprintf(buf, len, "%s (--set %s)", c->name, n->origin);
  else if (line > 0)
    snprintf(buf, len, "%s:%d:%d", c->name, line, col);
  else
    snprintf(buf, len, "%s", c->name);
}

/* Record "<where>: <path>: <what>"; exits in fatal mode. Always returns -1. */
static int vfail_at(struct cmn_case *c, const struct cmn_node *n, int use_key, const char *path,
                    const char *fmt, va_list ap) {
  char loc[1024], what[1024];
  where(c, n, use_key, loc, sizeof loc);
  vsnprintf(what, sizeof what, fmt, ap);
  if (path != NULL && path[0] != '\0')
    snprintf(c->err, sizeof c->err, "%s: %s: %s", loc, path, what);
  else
    snprintf(c->err, sizeof c->err, "%s: %s", loc, what);
  if (c->fatal) cmn_input_error("%s", c->err);
  return -1;
}

static int fail_at(struct cmn_case *c, const struct cmn_node *n, const char *path, const char *fmt,
                   ...) __attribute__((format(printf, 4, 5)));

static int fail_at(struct cmn_case *c, const struct cmn_node *n, const char *path, const char *fmt,
                   ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail_at(c, n, 0, path, fmt, ap);
  va_end(ap);
  return -1;
}

/* ---------------------------------------------------------------------------------------------
 * Paths: "a.b[2].c"
 * ------------------------------------------------------------------------------------------- */

struct segment {
  int is_index;
  const char *key; /**< not NUL-terminated */
  size_t keylen;
  long index;
};

/* Read the segment at *p (after a '.', or at the start). 1 if one was read, 0 at the end, -1 on
 * bad syntax. `first` is true at the start of the path. */
static int next_segment(const char **p, int first, struct segment *s) {
  const char *q = *p;
  if (*q == '\0') return first ? -1 : 0;
  if (*q == '[') {
    char *end = NULL;
    if (q[1] < '0' || q[1] > '9') return -1;
    long index = strtol(q + 1, &end, 10);
    if (*end != ']' || index < 0 || index > INT_MAX - 1) return -1;
    s->is_index = 1;
    s->index = index;
    *p = end + 1;
    return 1;
  }
  if (!first) {
    if (*q != '.') return -1;
    ++q;
  }
  size_t len = strcspn(q, ".[]");
  if (len == 0) return -1;
  s->is_index = 0;
  s->key = q;
  s->keylen = len;
  *p = q + len;
  return 1;
}

static int path_valid(const char *path) {
  if (path == NULL) return 0;
  const char *p = path;
  struct segment s = {0};
  int r, first = 1;
  while ((r = next_segment(&p, first, &s)) == 1) {
    if (first && s.is_index) return 0; /* the root is a mapping */
    first = 0;
  }
  return r == 0;
}

static const char *kind_name(const struct cmn_node *n) {
  switch (n->kind) {
    case NODE_MAP:
      return "a mapping";
    case NODE_SEQ:
      return "a sequence";
    default:
      return is_null(n) ? "an empty value" : "a scalar";
  }
}

/* Result of a lookup. */
struct found {
  struct cmn_node *node;   /**< the node at path, or NULL when absent */
  struct cmn_node *parent; /**< deepest existing node on the way (root at least) */
  size_t parent_len;       /**< length of the path prefix naming `parent` */
};

/* Walk the path. 0 when found or absent (f->node NULL), -1 when the path is malformed or goes
 * through a node of the wrong kind (error reported, so the caller just returns -1). */
static int lookup(struct cmn_case *c, const char *path, struct found *f) {
  f->node = NULL;
  f->parent = c->root;
  f->parent_len = 0;
  if (!path_valid(path)) return fail_at(c, NULL, path, "malformed key path");
  struct cmn_node *cur = c->root;
  const char *p = path;
  struct segment s = {0};
  int first = 1;
  while (next_segment(&p, first, &s) == 1) {
    size_t consumed = (size_t)(p - path);
    struct cmn_node *next = NULL;
    char prefix[512];
    snprintf(prefix, sizeof prefix, "%.*s", (int)f->parent_len, path);
    /* An empty value ("output:" with nothing below) is an empty section. */
    if (is_null(cur)) return 0;
    if (s.is_index) {
      if (cur->kind != NODE_SEQ)
        return fail_at(c, cur, prefix, "expected a sequence, got %s", kind_name(cur));
      if (s.index < cur->n) next = cur->items[s.index];
    } else {
      if (cur->kind != NODE_MAP)
        return fail_at(c, cur, prefix, "expected a mapping, got %s", kind_name(cur));
      next = map_find(cur, s.key, s.keylen);
    }
    first = 0;
    if (next == NULL) return 0;
    cur = next;
    f->parent = cur;
    f->parent_len = consumed;
  }
  f->node = cur;
  f->parent = NULL;
  return 0;
}

/* Find an existing node, or report the missing required key. 0 / -1. */
static int require(struct cmn_case *c, const char *path, struct cmn_node **node) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) {
    *node = f.node;
    return 0;
  }
  if (f.parent != c->root && node_line(f.parent) > 0)
    return fail_at(c, NULL, path, "required key missing (in '%.*s' at line %d)", (int)f.parent_len,
                   path, node_line(f.parent));
  return fail_at(c, NULL, path, "required key missing");
}

/* Put `node` at path, creating missing intermediate mappings (and appending to a sequence when the
 * index equals its length); an existing node is replaced. 0 / -1 (node freed on error). */
static int insert(struct cmn_case *c, const char *path, struct cmn_node *node) {
  if (!path_valid(path)) {
    node_free(node);
    return fail_at(c, NULL, path, "malformed key path");
  }
  /* First pass: check that the path can be built without touching the tree. */
  for (int pass = 0; pass < 2; ++pass) {
    struct cmn_node *cur = c->root;
    const char *p = path;
    struct segment s = {0};
    int first = 1, fresh = 0;
    while (next_segment(&p, first, &s) == 1) {
      first = 0;
      struct segment peek = {0};
      const char *q = p;
      int last = next_segment(&q, 0, &peek) != 1;
      /* Container created for the next segment if this one is missing. */
      enum node_kind want = peek.is_index ? NODE_SEQ : NODE_MAP;
      int slot = -1;
      if (fresh) {
        if (s.is_index && s.index != 0) {
          node_free(node);
          return fail_at(c, NULL, path, "index %ld out of range (new sequence)", s.index);
        }
      } else if (s.is_index) {
        if (cur->kind != NODE_SEQ) {
          node_free(node);
          return fail_at(c, cur, path, "cannot index %s", kind_name(cur));
        }
        if (s.index > cur->n) {
          node_free(node);
          return fail_at(c, cur, path, "index %ld out of range (the sequence has %d elements)",
                         s.index, cur->n);
        }
        if (s.index < cur->n) slot = (int)s.index;
      } else {
        if (cur->kind != NODE_MAP) {
          node_free(node);
          return fail_at(c, cur, path, "cannot set a key inside %s", kind_name(cur));
        }
        for (int i = 0; i < cur->n; ++i) {
          const char *k = cur->items[i]->key;
          if (strlen(k) == s.keylen && memcmp(k, s.key, s.keylen) == 0) slot = i;
        }
      }
      /* An empty value on the way becomes the container the rest of the path needs. */
      int null_slot = slot >= 0 && !last && is_null(cur->items[slot]);
      if (slot < 0 || null_slot) fresh = 1;
      if (pass == 0) {
        if (!fresh) cur = cur->items[slot];
        continue;
      }
      /* Second pass: build. */
      struct cmn_node *child;
      if (last) {
        child = node;
      } else if (slot >= 0 && !null_slot) {
        cur = cur->items[slot];
        continue;
      } else {
        child = node_new(want);
      }
      if (slot >= 0) {
        /* Replace, keeping the key and its position. */
        struct cmn_node *old = cur->items[slot];
        child->key = old->key;
        child->key_line = old->key_line;
        child->key_col = old->key_col;
        old->key = NULL;
        node_free(old);
        cur->items[slot] = child;
      } else {
        if (!s.is_index) child->key = dup_n(s.key, s.keylen);
        node_append(cur, child);
      }
      cur = child;
    }
  }
  return 0;
}

/* ---------------------------------------------------------------------------------------------
 * Public lookups
 * ------------------------------------------------------------------------------------------- */

/* Quiet lookup: the node at path, or NULL (absent, malformed path or wrong kind on the way). */
static struct cmn_node *find(const struct cmn_case *c, const char *path) {
  if (!path_valid(path)) return NULL;
  struct cmn_node *cur = c->root;
  const char *p = path;
  struct segment s = {0};
  int first = 1;
  while (cur != NULL && next_segment(&p, first, &s) == 1) {
    first = 0;
    if (s.is_index)
      cur = cur->kind == NODE_SEQ && s.index < cur->n ? cur->items[s.index] : NULL;
    else
      cur = cur->kind == NODE_MAP ? map_find(cur, s.key, s.keylen) : NULL;
  }
  return cur;
}

int cmn_case_has(const struct cmn_case *c, const char *path) { return find(c, path) != NULL; }

void cmn_case_mark_used(struct cmn_case *c, const char *path) {
  struct cmn_node *n = find(c, path);
  if (n != NULL) mark_tree(n);
}

int cmn_case_line(const struct cmn_case *c, const char *path) {
  const struct cmn_node *n = find(c, path);
  return n != NULL && n->origin == NULL ? node_line(n) : 0;
}

int cmn_case_fail(struct cmn_case *c, const char *path, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vfail_at(c, find(c, path), 0, path, fmt, ap);
  va_end(ap);
  return -1;
}

int cmn_case_seq_length(struct cmn_case *c, const char *path) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node == NULL) return 0;
  f.node->used = 1;
  if (is_null(f.node)) return 0;
  if (f.node->kind != NODE_SEQ)
    return fail_at(c, f.node, path, "expected a sequence, got %s", kind_name(f.node));
  return f.node->n;
}

int cmn_case_is_map(struct cmn_case *c, const char *path) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node == NULL) return 0;
  f.node->used = 1;
  if (is_null(f.node)) return 0;
  if (f.node->kind != NODE_MAP)
    return fail_at(c, f.node, path, "expected a mapping, got %s", kind_name(f.node));
  return 1;
}

/* ---------------------------------------------------------------------------------------------
 * Typed getters
 * ------------------------------------------------------------------------------------------- */

/* Describe a found node for "got ..." : its text for a scalar, its kind otherwise. */
static void describe(const struct cmn_node *n, char *buf, size_t len) {
  if (n->kind == NODE_SCALAR && !is_null(n))
    snprintf(buf, len, "'%s'", n->value);
  else
    snprintf(buf, len, "%s", kind_name(n));
}

static void range_text(double lo, double hi, const char *what, char *buf, size_t len) {
  if (lo == -INFINITY && hi == INFINITY)
    snprintf(buf, len, "%s", what);
  else if (hi == INFINITY)
    snprintf(buf, len, "%s >= %.17g", what, lo);
  else if (lo == -INFINITY)
    snprintf(buf, len, "%s <= %.17g", what, hi);
  else
    snprintf(buf, len, "%s in [%.17g, %.17g]", what, lo, hi);
}

/* Shortest of %.15g, %.16g, %.17g that reads back to the same double. */
static void format_double(double x, char *buf, size_t len) {
  for (int prec = 15; prec <= 17; ++prec) {
    snprintf(buf, len, "%.*g", prec, x);
    double y;
    if (cmn_parse_double(buf, &y) == 0 && y == x) return;
  }
}

/* Read a number from a node; `positive` selects the "positive number" wording and x > 0. */
static int node_double(struct cmn_case *c, struct cmn_node *n, const char *path, double lo,
                       double hi, int positive, double *value) {
  n->used = 1;
  char what[128], got[512];
  if (positive)
    snprintf(what, sizeof what, "a positive number");
  else
    range_text(lo, hi, "a number", what, sizeof what);
  double x;
  if (n->kind != NODE_SCALAR || cmn_parse_double(n->value, &x) != 0 ||
      (positive ? !(x > 0.0) : (x < lo || x > hi))) {
    describe(n, got, sizeof got);
    return fail_at(c, n, path, "expected %s, got %s", what, got);
  }
  *value = x;
  return 0;
}

int cmn_case_get_double(struct cmn_case *c, const char *path, double lo, double hi, double *value) {
  struct cmn_node *n = NULL;
  if (require(c, path, &n) != 0) return -1;
  return node_double(c, n, path, lo, hi, 0, value);
}

int cmn_case_opt_double(struct cmn_case *c, const char *path, double def, double lo, double hi,
                        double *value) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) return node_double(c, f.node, path, lo, hi, 0, value);
  char text[64];
  format_double(def, text, sizeof text);
  struct cmn_node *n = scalar_new(text, 0);
  n->used = 1;
  if (insert(c, path, n) != 0) return -1;
  *value = def;
  return 0;
}

int cmn_case_get_positive(struct cmn_case *c, const char *path, double *value) {
  struct cmn_node *n = NULL;
  if (require(c, path, &n) != 0) return -1;
  return node_double(c, n, path, 0.0, INFINITY, 1, value);
}

int cmn_case_opt_positive(struct cmn_case *c, const char *path, double def, double *value) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) return node_double(c, f.node, path, 0.0, INFINITY, 1, value);
  return cmn_case_opt_double(c, path, def, -INFINITY, INFINITY, value);
}

/* Integers: decimal text, or a number in exponent form that is exactly a whole number ("1e6"). */
static int node_long(struct cmn_case *c, struct cmn_node *n, const char *path, long lo, long hi,
                     long *value) {
  n->used = 1;
  long x = 0;
  int ok = 0;
  if (n->kind == NODE_SCALAR) {
    if (cmn_parse_long(n->value, LONG_MIN, LONG_MAX, &x) == 0) {
      ok = 1;
    } else {
      double d;
      if (cmn_parse_double(n->value, &d) == 0 && d == floor(d) && fabs(d) <= 0x1p53) {
        x = (long)d;
        ok = 1;
      }
    }
  }
  if (!ok || x < lo || x > hi) {
    char got[512];
    describe(n, got, sizeof got);
    if (lo == LONG_MIN && hi == LONG_MAX)
      return fail_at(c, n, path, "expected an integer, got %s", got);
    if (hi == LONG_MAX) return fail_at(c, n, path, "expected an integer >= %ld, got %s", lo, got);
    if (lo == LONG_MIN) return fail_at(c, n, path, "expected an integer <= %ld, got %s", hi, got);
    return fail_at(c, n, path, "expected an integer in [%ld, %ld], got %s", lo, hi, got);
  }
  *value = x;
  return 0;
}

int cmn_case_get_long(struct cmn_case *c, const char *path, long lo, long hi, long *value) {
  struct cmn_node *n = NULL;
  if (require(c, path, &n) != 0) return -1;
  return node_long(c, n, path, lo, hi, value);
}

int cmn_case_opt_long(struct cmn_case *c, const char *path, long def, long lo, long hi,
                      long *value) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) return node_long(c, f.node, path, lo, hi, value);
  char text[32];
  snprintf(text, sizeof text, "%ld", def);
  struct cmn_node *n = scalar_new(text, 0);
  n->used = 1;
  if (insert(c, path, n) != 0) return -1;
  *value = def;
  return 0;
}

static int node_bool(struct cmn_case *c, struct cmn_node *n, const char *path, int *value) {
  static const char *const yes[] = {"true", "yes", "on"};
  static const char *const no[] = {"false", "no", "off"};
  n->used = 1;
  if (n->kind == NODE_SCALAR) {
    for (int i = 0; i < 3; ++i) {
      if (strcasecmp(n->value, yes[i]) == 0) {
        *value = 1;
        return 0;
      }
      if (strcasecmp(n->value, no[i]) == 0) {
        *value = 0;
        return 0;
      }
    }
  }
  char got[512];
  describe(n, got, sizeof got);
  return fail_at(c, n, path, "expected a boolean (true/false, yes/no, on/off), got %s", got);
}

int cmn_case_get_bool(struct cmn_case *c, const char *path, int *value) {
  struct cmn_node *n = NULL;
  if (require(c, path, &n) != 0) return -1;
  return node_bool(c, n, path, value);
}

int cmn_case_opt_bool(struct cmn_case *c, const char *path, int def, int *value) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) return node_bool(c, f.node, path, value);
  struct cmn_node *n = scalar_new(def ? "true" : "false", 0);
  n->used = 1;
  if (insert(c, path, n) != 0) return -1;
  *value = def != 0;
  return 0;
}

static int node_string(struct cmn_case *c, struct cmn_node *n, const char *path,
                       const char **value) {
  n->used = 1;
  if (n->kind != NODE_SCALAR || is_null(n))
    return fail_at(c, n, path, "expected a string, got %s", kind_name(n));
  *value = n->value;
  return 0;
}

int cmn_case_get_string(struct cmn_case *c, const char *path, const char **value) {
  struct cmn_node *n = NULL;
  if (require(c, path, &n) != 0) return -1;
  return node_string(c, n, path, value);
}

int cmn_case_opt_string(struct cmn_case *c, const char *path, const char *def, const char **value) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) return node_string(c, f.node, path, value);
  /* Quoted, so that a default such as "on" or "1" stays a string when read back. */
  struct cmn_node *n = scalar_new(def != NULL ? def : "", 1);
  n->used = 1;
  if (insert(c, path, n) != 0) return -1;
  *value = n->value;
  return 0;
}

static int node_choice(struct cmn_case *c, struct cmn_node *n, const char *path,
                       const char *const *names, int *index) {
  n->used = 1;
  if (n->kind == NODE_SCALAR && !is_null(n)) {
    for (int i = 0; names[i] != NULL; ++i) {
      if (strcmp(n->value, names[i]) == 0) {
        *index = i;
        return 0;
      }
    }
  }
  char list[1024] = "", got[512];
  size_t used = 0;
  for (int i = 0; names[i] != NULL && used < sizeof list; ++i)
    used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i > 0 ? ", " : "", names[i]);
  describe(n, got, sizeof got);
  return fail_at(c, n, path, "expected one of: %s; got %s", list, got);
}

int cmn_case_get_choice(struct cmn_case *c, const char *path, const char *const *names,
                        int *index) {
  struct cmn_node *n = NULL;
  if (require(c, path, &n) != 0) return -1;
  return node_choice(c, n, path, names, index);
}

int cmn_case_opt_choice(struct cmn_case *c, const char *path, const char *const *names, int def,
                        int *index) {
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) return node_choice(c, f.node, path, names, index);
  int count = 0;
  while (names[count] != NULL) ++count;
  if (def < 0 || def >= count) cmn_error("%s: default choice %d out of range", path, def);
  struct cmn_node *n = scalar_new(names[def], 0);
  n->used = 1;
  if (insert(c, path, n) != 0) return -1;
  *index = def;
  return 0;
}

static int node_doubles(struct cmn_case *c, struct cmn_node *n, const char *path, int count_n,
                        int max, double *values, int *count) {
  n->used = 1;
  int lo = count_n > 0 ? count_n : 1, hi = count_n > 0 ? count_n : max;
  if (n->kind != NODE_SEQ || n->n < lo || n->n > hi) {
    char got[512];
    if (n->kind == NODE_SEQ)
      snprintf(got, sizeof got, "%d element%s", n->n, n->n == 1 ? "" : "s");
    else
      describe(n, got, sizeof got);
    if (lo == hi)
      return fail_at(c, n, path, "expected a sequence of %d number%s, got %s", lo,
                     lo == 1 ? "" : "s", got);
    return fail_at(c, n, path, "expected a sequence of %d to %d numbers, got %s", lo, hi, got);
  }
  for (int i = 0; i < n->n; ++i) {
    struct cmn_node *e = n->items[i];
    char epath[512];
    snprintf(epath, sizeof epath, "%s[%d]", path, i);
    double x;
    if (node_double(c, e, epath, -INFINITY, INFINITY, 0, &x) != 0) return -1;
  }
  for (int i = 0; i < n->n; ++i) cmn_parse_double(n->items[i]->value, &values[i]);
  if (count != NULL) *count = n->n;
  return 0;
}

int cmn_case_get_doubles(struct cmn_case *c, const char *path, int n, int max, double *values,
                         int *count) {
  if (n < 0 || (n == 0 && max <= 0))
    cmn_error("%s: bad element count n = %d, max = %d", path, n, max);
  struct cmn_node *node = NULL;
  if (require(c, path, &node) != 0) return -1;
  return node_doubles(c, node, path, n, max, values, count);
}

int cmn_case_opt_doubles(struct cmn_case *c, const char *path, int n, const double *def,
                         double *values) {
  if (n <= 0) cmn_error("%s: bad element count n = %d", path, n);
  struct found f;
  if (lookup(c, path, &f) != 0) return -1;
  if (f.node != NULL) return node_doubles(c, f.node, path, n, n, values, NULL);
  struct cmn_node *seq = node_new(NODE_SEQ);
  seq->used = 1;
  for (int i = 0; i < n; ++i) {
    char text[64];
    format_double(def[i], text, sizeof text);
    struct cmn_node *e = scalar_new(text, 0);
    e->used = 1;
    node_append(seq, e);
  }
  if (insert(c, path, seq) != 0) return -1;
  for (int i = 0; i < n; ++i) values[i] = def[i];
  return 0;
}

/* ---------------------------------------------------------------------------------------------
 * --set overrides
 * ------------------------------------------------------------------------------------------- */

int cmn_case_set(struct cmn_case *c, const char *assignment) {
  const char *eq = assignment != NULL ? strchr(assignment, '=') : NULL;
  if (eq == NULL)
    return fail_at(c, NULL, NULL, "--set '%s': expected key=value",
                   assignment != NULL ? assignment : "");
  /* Keep the assignment: the new nodes name it as their origin. */
  char *origin = dup_s(assignment);
  c->sets = cmn_realloc(c->sets, (size_t)(c->nsets + 1) * sizeof *c->sets);
  c->sets[c->nsets++] = origin;

  const char *k0 = assignment, *k1 = eq;
  while (k0 < k1 && (*k0 == ' ' || *k0 == '\t')) ++k0;
  while (k1 > k0 && (k1[-1] == ' ' || k1[-1] == '\t')) --k1;
  char path[512];
  if (k1 == k0) return fail_at(c, NULL, NULL, "--set '%s': empty key", assignment);
  if ((size_t)(k1 - k0) >= sizeof path)
    return fail_at(c, NULL, NULL, "--set '%s': key too long", assignment);
  memcpy(path, k0, (size_t)(k1 - k0));
  path[k1 - k0] = '\0';
  if (!path_valid(path))
    return fail_at(c, NULL, NULL, "--set '%s': malformed key path '%s'", assignment, path);

  char err[1024];
  struct builder b = {.name = "value", .origin = origin, .err = err, .errlen = sizeof err};
  struct cmn_node *value = NULL;
  if (build_document(&b, eq + 1, strlen(eq + 1), &value) != 0)
    return fail_at(c, NULL, NULL, "--set '%s': cannot parse the value: %s", assignment, err);
  if (value == NULL) value = scalar_new("", 0); /* "key=" gives an empty (null) value */
  set_origin(value, origin);
  return insert(c, path, value);
}

/* ---------------------------------------------------------------------------------------------
 * Unused keys
 * ------------------------------------------------------------------------------------------- */

static int any_used(const struct cmn_node *n) {
  if (n->used) return 1;
  for (int i = 0; i < n->n; ++i)
    if (any_used(n->items[i])) return 1;
  return 0;
}

/* First node in document order that nothing read; its path is built in `path`. */
static const struct cmn_node *first_unused(const struct cmn_node *n, char *path, size_t len) {
  size_t base = strlen(path);
  for (int i = 0; i < n->n; ++i) {
    const struct cmn_node *child = n->items[i];
    if (n->kind == NODE_MAP)
      snprintf(path + base, len - base, "%s%s", base > 0 ? "." : "", child->key);
    else
      snprintf(path + base, len - base, "[%d]", i);
    if (!any_used(child)) return child;
    if (child->kind != NODE_SCALAR) {
      const struct cmn_node *u = first_unused(child, path, len);
      if (u != NULL) return u;
    }
  }
  path[base] = '\0';
  return NULL;
}

int cmn_case_check_unused(struct cmn_case *c) {
  char path[1024] = "";
  const struct cmn_node *n = first_unused(c->root, path, sizeof path);
  if (n == NULL) return 0;
  char loc[1024];
  where(c, n, n->key != NULL, loc, sizeof loc);
  snprintf(c->err, sizeof c->err, "%s: unknown key '%s'", loc, path);
  if (c->fatal) cmn_input_error("%s", c->err);
  return -1;
}

/* ---------------------------------------------------------------------------------------------
 * Writing used_case.yaml
 * ------------------------------------------------------------------------------------------- */

/* ---------------------------------------------------------------------------------------------
 * Digest
 * ------------------------------------------------------------------------------------------- */
static unsigned long long fnv(unsigned long long h, const void *data, size_t len) {
  const unsigned char *b = data;
  for (size_t i = 0; i < len; ++i) h = (h ^ b[i]) * 1099511628211ULL;
  return h;
}

static unsigned long long digest_node(unsigned long long h, const struct cmn_node *n) {
  unsigned char kind = (unsigned char)n->kind;
  h = fnv(h, &kind, 1);
  if (n->kind == NODE_SCALAR) {
    double x;
    if (!n->quoted && cmn_parse_double(n->value, &x) == 0) {
      x = x == 0.0 ? 0.0 : x; /* -0 reads as 0 */
      unsigned char tag = 'n';
      h = fnv(fnv(h, &tag, 1), &x, sizeof x);
    } else {
      h = fnv(h, n->value, strlen(n->value) + 1);
    }
    return h;
  }
  for (int i = 0; i < n->n; ++i) {
    if (n->kind == NODE_MAP) h = fnv(h, n->items[i]->key, strlen(n->items[i]->key) + 1);
    h = digest_node(h, n->items[i]);
  }
  unsigned char end = 0xff;
  return fnv(h, &end, 1);
}

unsigned long long cmn_case_digest(const struct cmn_case *c, const char *path) {
  const struct cmn_node *n = path[0] ? find(c, path) : c->root;
  if (n == NULL) return 0;
  unsigned long long h = digest_node(14695981039346656037ULL, n);
  return h ? h : 1;
}

int cmn_case_top_count(const struct cmn_case *c) {
  return c->root->kind == NODE_MAP ? c->root->n : 0;
}

const char *cmn_case_top_key(const struct cmn_case *c, int i) {
  if (c->root->kind != NODE_MAP || i < 0 || i >= c->root->n) return NULL;
  return c->root->items[i]->key;
}

struct sink {
  FILE *out;
  int failed;
};

static int write_handler(void *data, unsigned char *buffer, size_t size) {
  struct sink *s = data;
  if (fwrite(buffer, 1, size, s->out) != size) s->failed = 1;
  return !s->failed;
}

static int emit(yaml_emitter_t *e, yaml_event_t *ev) { return yaml_emitter_emit(e, ev) ? 0 : -1; }

static int emit_scalar(yaml_emitter_t *e, const char *text, int quoted) {
  yaml_event_t ev;
  yaml_scalar_style_t style = quoted ? YAML_DOUBLE_QUOTED_SCALAR_STYLE : YAML_ANY_SCALAR_STYLE;
  if (!yaml_scalar_event_initialize(&ev, NULL, NULL, (yaml_char_t *)text, (int)strlen(text),
                                    !quoted, quoted, style))
    return -1;
  return emit(e, &ev);
}

static int emit_node(yaml_emitter_t *e, const struct cmn_node *n) {
  yaml_event_t ev;
  if (n->kind == NODE_SCALAR) return emit_scalar(e, n->value, n->quoted);
  if (n->kind == NODE_SEQ) {
    /* Vectors on one line ("[0, 1.5, 2]"), anything deeper in block style. */
    int flat = 1;
    for (int i = 0; i < n->n; ++i) flat = flat && n->items[i]->kind == NODE_SCALAR;
    if (!yaml_sequence_start_event_initialize(
            &ev, NULL, NULL, 1, flat ? YAML_FLOW_SEQUENCE_STYLE : YAML_BLOCK_SEQUENCE_STYLE))
      return -1;
    if (emit(e, &ev) != 0) return -1;
    for (int i = 0; i < n->n; ++i)
      if (emit_node(e, n->items[i]) != 0) return -1;
    if (!yaml_sequence_end_event_initialize(&ev)) return -1;
    return emit(e, &ev);
  }
  if (!yaml_mapping_start_event_initialize(&ev, NULL, NULL, 1, YAML_BLOCK_MAPPING_STYLE)) return -1;
  if (emit(e, &ev) != 0) return -1;
  for (int i = 0; i < n->n; ++i) {
    if (emit_scalar(e, n->items[i]->key, 0) != 0) return -1;
    if (emit_node(e, n->items[i]) != 0) return -1;
  }
  if (!yaml_mapping_end_event_initialize(&ev)) return -1;
  return emit(e, &ev);
}

int cmn_case_write(const struct cmn_case *c, FILE *out) {
  yaml_emitter_t e;
  struct sink s = {out, 0};
  if (!yaml_emitter_initialize(&e)) return -1;
  yaml_emitter_set_output(&e, write_handler, &s);
  yaml_emitter_set_unicode(&e, 1);
  yaml_emitter_set_width(&e, -1);
  yaml_event_t ev;
  int status = -1;
  if (yaml_stream_start_event_initialize(&ev, YAML_UTF8_ENCODING) && emit(&e, &ev) == 0 &&
      yaml_document_start_event_initialize(&ev, NULL, NULL, NULL, 1) && emit(&e, &ev) == 0 &&
      emit_node(&e, c->root) == 0 && yaml_document_end_event_initialize(&ev, 1) &&
      emit(&e, &ev) == 0 && yaml_stream_end_event_initialize(&ev) && emit(&e, &ev) == 0 &&
      yaml_emitter_flush(&e))
    status = 0;
  yaml_emitter_delete(&e);
  if (s.failed || fflush(out) != 0 || ferror(out)) status = -1;
  return status;
}

int cmn_case_write_file(const struct cmn_case *c, const char *path) {
  FILE *f = fopen(path, "w");
  if (f == NULL) return -1;
  int status = cmn_case_write(c, f);
  if (fclose(f) != 0) status = -1;
  return status;
}
