/*
 * SABRE common/ — the one small layer both applications (fv1d, sph) share:
 *   1. messages and fatal errors (SWIFT-style error() naming file, function and line);
 *   2. case files: YAML read through libyaml into a small tree, typed getters by path that report
 *      the file, line and expected type, documented defaults written back into the tree (so the
 *      resolved parameters can be saved as used_case.yaml), `--set key=value` overrides, and a
 *      final check that every key of the file was used (a typo must not fall back to a default),
 *      and the command line shared by the case-file programs (cmn_cli_*);
 *   3. CSV writing (full double precision), CSV table reading (numeric tables with a header, and
 *      linear interpolation in them), and progress lines with ETA on stderr;
 *   4. expressions of named variables for initial profiles in case files (cmn_expr_*).
 *
 * This layer belongs to the applications: unlike riemann/, its fatal helpers may exit.
 */
#ifndef SABRE_COMMON_H
#define SABRE_COMMON_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Messages and errors
 * ------------------------------------------------------------------------------------------- */

/** Exit code for bad input (CLI flags, case files, geometry files, non-physical parameters). */
#define CMN_EXIT_INPUT 2
/** Exit code for a run that failed (NaN, lost particle, solver failure, I/O error). */
#define CMN_EXIT_FAILURE 1
/**
 * Exit code for a run stopped at time.max_steps before time.end (both programs): the outputs are
 * complete and consistent up to the time reached (sabre-sph also writes a checkpoint), but the run
 * did not reach time.end.
 */
#define CMN_EXIT_INCOMPLETE 3

/** Set the program name used as prefix of every message (default "sabre"). */
void cmn_set_program_name(const char *name);
/** The program name set by cmn_set_program_name(). */
const char *cmn_program_name(void);
/** Print "<prog> <version>" on stdout (--version). */
void cmn_print_version(void);
/**
 * Flush stdout and check it for write errors (a full disk, `> /dev/full`, a closed pipe): returns
 * `status` if all went well, else prints "<prog>: error: cannot write the output: <why>" and
 * returns CMN_EXIT_FAILURE. For the end of commands that print results on stdout.
 */
int cmn_stdout_status(int status);
/** Informational message on stderr, prefixed with the program name; newline appended. */
void cmn_message(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/** Warning on stderr ("<prog>: warning: ..."). */
void cmn_warning(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/** Bad user input: "<prog>: error: ..." on stderr, exit(CMN_EXIT_INPUT). */
_Noreturn void cmn_input_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/** Internal or run failure with source location; exit(CMN_EXIT_FAILURE). Use via cmn_error(). */
_Noreturn void cmn_fatal_at(const char *file, const char *func, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
#define cmn_error(...)                                       \
  do {                                                       \
    cmn_fatal_at(__FILE__, __func__, __LINE__, __VA_ARGS__); \
  } while (0)

/** malloc/calloc/realloc that call cmn_error() on failure (never return NULL for n > 0). */
void *cmn_malloc(size_t n);
void *cmn_calloc(size_t count, size_t size);
void *cmn_realloc(void *p, size_t n);

/**
 * Strict number parsing for CLI values: the whole string must be a finite number.
 * Returns 0 on success, -1 otherwise (value untouched).
 */
int cmn_parse_double(const char *text, double *value);
/** Parse a comma-separated list of at most `max` finite numbers; returns the count or -1. */
int cmn_parse_doubles(const char *text, double *values, int max);
/** Parse a whole-number string into a long in [lo, hi]; 0 on success, -1 otherwise. */
int cmn_parse_long(const char *text, long lo, long hi, long *value);

/** mkdir -p; returns 0 on success, -1 with errno set. */
int cmn_mkdir_p(const char *path);

/* ---------------------------------------------------------------------------------------------
 * Case files
 *
 * Paths address the tree: "fluid.c0", "boundaries.left.type", "regions[1].min" (sequence index).
 * Getters return 0 on success and -1 on error. On error the case keeps a message such as
 *   case.yaml:12:7: fluid.c0: expected a positive number, got 'abc'
 * (cmn_case_error()). In fatal mode (the default, cmn_case_set_fatal) any error prints that
 * message and exits with CMN_EXIT_INPUT, so applications need not check return values; tests turn
 * fatal mode off and check them.
 *
 * Optional getters (`_opt_`) insert the default into the tree when the key is absent, so
 * cmn_case_write() gives the fully resolved parameters. Every node a getter reads is marked used;
 * cmn_case_check_unused() then reports the first key of the file no getter asked for.
 * ------------------------------------------------------------------------------------------- */
struct cmn_case;

/** Load and parse a YAML file. On failure returns NULL and, if err != NULL, writes a message
 *  "<path>:<line>:<col>: <what>" into err (size errlen). The root must be a mapping. */
struct cmn_case *cmn_case_load(const char *path, char *err, size_t errlen);
/** Parse YAML text; `name` stands for the file name in messages. Same error contract. */
struct cmn_case *cmn_case_parse(const char *text, const char *name, char *err, size_t errlen);
/** Free the case (NULL accepted). Strings returned by getters die with it. */
void cmn_case_free(struct cmn_case *c);
/** Fatal mode on (1, default) or off (0). */
void cmn_case_set_fatal(struct cmn_case *c, int fatal);
/** Last error message ("" if none). Owned by the case. */
const char *cmn_case_error(const struct cmn_case *c);
/** File name given at load/parse. */
const char *cmn_case_name(const struct cmn_case *c);

/**
 * Apply an override "path=value" (CLI --set). The value is parsed as YAML (scalar, or flow
 * sequence/mapping such as "[1, 2]"); missing intermediate mappings are created; an existing node
 * is replaced. Errors: no '=', empty path, bad path syntax, unparsable value.
 */
int cmn_case_set(struct cmn_case *c, const char *assignment);

/** 1 if the path exists, else 0 (does not mark it used). */
int cmn_case_has(const struct cmn_case *c, const char *path);
/** Mark a path and everything below it used (for sections read by a generic reader). */
void cmn_case_mark_used(struct cmn_case *c, const char *path);

/** Required finite number in [lo, hi] (use -INFINITY/INFINITY for no bound). */
int cmn_case_get_double(struct cmn_case *c, const char *path, double lo, double hi, double *value);
/** Optional finite number in [lo, hi], default `def` when absent. */
int cmn_case_opt_double(struct cmn_case *c, const char *path, double def, double lo, double hi,
                        double *value);
/** Required / optional number > 0. */
int cmn_case_get_positive(struct cmn_case *c, const char *path, double *value);
int cmn_case_opt_positive(struct cmn_case *c, const char *path, double def, double *value);
/** Required / optional integer in [lo, hi]. */
int cmn_case_get_long(struct cmn_case *c, const char *path, long lo, long hi, long *value);
int cmn_case_opt_long(struct cmn_case *c, const char *path, long def, long lo, long hi,
                      long *value);
/** Required / optional boolean (true/false, yes/no, on/off). */
int cmn_case_get_bool(struct cmn_case *c, const char *path, int *value);
int cmn_case_opt_bool(struct cmn_case *c, const char *path, int def, int *value);
/** Required / optional string (scalar); the pointer is owned by the case. */
int cmn_case_get_string(struct cmn_case *c, const char *path, const char **value);
int cmn_case_opt_string(struct cmn_case *c, const char *path, const char *def, const char **value);
/**
 * Required / optional choice among a NULL-terminated list of names; *index receives the
 * position. Error: "expected one of: a, b, c".
 */
int cmn_case_get_choice(struct cmn_case *c, const char *path, const char *const *names, int *index);
int cmn_case_opt_choice(struct cmn_case *c, const char *path, const char *const *names, int def,
                        int *index);
/**
 * Required / optional sequence of exactly n numbers (n > 0), or of 1..max numbers when n == 0
 * (count returned in *count, may be NULL when n > 0). The optional form fills `def` (n values).
 */
int cmn_case_get_doubles(struct cmn_case *c, const char *path, int n, int max, double *values,
                         int *count);
int cmn_case_opt_doubles(struct cmn_case *c, const char *path, int n, const double *def,
                         double *values);
/** Length of the sequence at path (0 when absent); -1 (error) if the node is not a sequence. */
int cmn_case_seq_length(struct cmn_case *c, const char *path);
/** 1 if path is a mapping, 0 if absent; error (-1) if it exists but is not a mapping. */
int cmn_case_is_map(struct cmn_case *c, const char *path);
/** Line (1-based) of the node at path in the file, 0 if absent or inserted. */
int cmn_case_line(const struct cmn_case *c, const char *path);
/** Report an application-level error about a key ("<file>:<line>:<col>: <path>: <msg>");
 *  returns -1 (exits in fatal mode). For constraints between keys, e.g. "must exceed x_min". */
int cmn_case_fail(struct cmn_case *c, const char *path, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/** Error naming the first key of the file (in document order) that no getter read. 0 if none. */
int cmn_case_check_unused(struct cmn_case *c);
/**
 * 64-bit digest (FNV-1a) of the subtree at `path` ("" for the whole case): kinds, keys in order
 * and values, where a scalar that reads as a number counts by its value ("0.3" and "3e-1" are the
 * same). 0 when the path is absent. For checking that a restart uses the parameters of the run it
 * continues.
 */
unsigned long long cmn_case_digest(const struct cmn_case *c, const char *path);
/** Number of top-level keys, and the name of the i-th (NULL if out of range). */
int cmn_case_top_count(const struct cmn_case *c);
const char *cmn_case_top_key(const struct cmn_case *c, int i);
/** Write the tree (with defaults filled in) as YAML. 0 on success, -1 on I/O error. */
int cmn_case_write(const struct cmn_case *c, FILE *out);
/** Write it to a file path. 0 / -1. */
int cmn_case_write_file(const struct cmn_case *c, const char *path);

/* ---------------------------------------------------------------------------------------------
 * Command lines of the case-file programs (sabre-fv1d, sabre-sph run|scalar|mesh):
 *
 *   <program> CASE.yaml [--set key=value]... [--output DIR] [<option> [VALUE]]...
 *
 * in three steps: cmn_cli_parse() reads the arguments, cmn_cli_load() loads the case and applies
 * the --set overrides in order, and, once the application has read the case (filling in its
 * defaults), cmn_cli_write_used() creates the run directory and writes DIR/used_case.yaml.
 * Options may come in any order; each may be given once (--set may repeat): a repeated option is an
 * error, never a silent override. --help prints the usage, --version the program's version.
 * Bad input is reported
 * through cmn_input_error() (exit CMN_EXIT_INPUT), so these calls return only on success.
 * ------------------------------------------------------------------------------------------- */

/** An option of one program beyond --set and --output. */
struct cmn_cli_option {
  const char *name;   /**< with its dashes, e.g. "--threads" */
  const char **value; /**< receives the argument after the option, or `name` itself for a flag;
                           left alone when the option is absent */
  int flag;           /**< 0: takes one argument ("--threads N"); 1: takes none ("--quiet") */
};

/** A parsed command line. */
struct cmn_cli {
  const char *command;   /**< prefix of the messages ("run"), or NULL for none */
  const char *case_path; /**< the one positional argument (a pointer into argv) */
  const char *output;    /**< --output, or the program's default (pointer into argv or default) */
  int nsets;             /**< number of --set assignments */
  const char **sets;     /**< the --set assignments in order: array owned (freed by cmn_cli_load),
                              strings in argv */
};

/**
 * Parse argv[1 .. argc) (argv[0] is the program or command name and is skipped): one case file,
 * --set (repeatable), --output and the `noptions` options of `options` (NULL when none). Messages
 * start with "<command>: " when command != NULL. Returns 1 if --help or -h was given (then `usage`
 * is printed on stdout and nothing is left to free) or --version (then the version is), else 0
 * with *cli filled in.
 * Errors (exit CMN_EXIT_INPUT, message on stderr, "[<command>: ]" first):
 *   "--set: missing value (see --help)"               an option that takes a value ends argv;
 *   "unknown option '--x' (see --help)"               any other argument starting with '-';
 *   "--output given twice: give each option once"     a repeated option other than --set;
 *   "one case file only ('a.yaml' and 'b.yaml')"      a second positional argument;
 *   "missing case file (see --help)"                  none.
 */
int cmn_cli_parse(struct cmn_cli *cli, int argc, char **argv, const char *command,
                  const char *usage, const char *default_output,
                  const struct cmn_cli_option *options, int noptions);
/**
 * Load cli->case_path and apply the --set assignments in order; frees cli->sets (nsets becomes
 * 0). Returns the case in fatal mode, owned by the caller (cmn_case_free()). Errors (exit
 * CMN_EXIT_INPUT): the message of cmn_case_load() (file missing, unreadable, not YAML, root not a
 * mapping) or of cmn_case_set() (e.g. "case.yaml: --set 'a': expected key=value").
 */
struct cmn_case *cmn_cli_load(struct cmn_cli *cli);
/**
 * Create the run directory `dir` (mkdir -p) and write the case, as used so far, into
 * dir/used_case.yaml. Errors (exit CMN_EXIT_INPUT) say why: "cannot create the output directory
 * 'dir': Permission denied", "cannot write 'dir/used_case.yaml': No space left on device".
 */
void cmn_cli_write_used(const struct cmn_case *c, const char *dir);

/* ---------------------------------------------------------------------------------------------
 * CSV output
 * ------------------------------------------------------------------------------------------- */
struct cmn_csv;

/** Create/truncate `path` and write the header line from `ncols` column names. NULL on failure
 *  (errno set). */
struct cmn_csv *cmn_csv_open(const char *path, int ncols, const char *const *names);
/** Append one row of ncols numbers, printed with %.17g (round-trip exact). 0 / -1. */
int cmn_csv_row(struct cmn_csv *csv, const double *values);
/** Flush to the OS (for long runs). 0 / -1. */
int cmn_csv_flush(struct cmn_csv *csv);
/** Close; returns -1 if any write failed. NULL accepted. */
int cmn_csv_close(struct cmn_csv *csv);

/* ---------------------------------------------------------------------------------------------
 * CSV tables (input): time tables of imposed values, initial profiles, probe lists.
 *
 * The format is the one cmn_csv_open()/cmn_csv_row() write (docs/case-files.md, "Table files"):
 *   - blank lines, and lines whose first non-blank character is '#', are skipped anywhere;
 *   - the first other line is the header: ncols ≥ 1 comma-separated column names, non-empty and
 *     distinct; a name may be quoted as in RFC 4180 ("u, m/s", "say ""hi""");
 *   - every later line is a row of exactly ncols finite numbers (as for case-file numbers:
 *     decimal or exponent notation, no nan/inf, nothing that overflows); blanks around a cell are
 *     ignored; there is at least one row.
 * Lines end in LF or CRLF; a UTF-8 byte-order mark is skipped.
 *
 * Errors name the file, the line and, for a cell, the column (1-based) and its name:
 *   tab.csv:7: column 2 ('p'): expected a number, got 'abc'
 *   tab.csv:9: expected 3 cells as in the header (line 2), got 2
 * ------------------------------------------------------------------------------------------- */
struct cmn_table {
  char *path;       /**< file name as given to cmn_table_read(), for messages */
  int ncols;        /**< number of columns (≥ 1) */
  size_t nrows;     /**< number of data rows (≥ 1) */
  char **names;     /**< the ncols column names, unquoted */
  double *data;     /**< nrows × ncols values, row-major: row i, column j at data[i * ncols + j] */
  long *lines;      /**< file line (1-based) of each row, for messages about a row */
  long header_line; /**< file line of the header */
};

/**
 * Read a table file into *t, which is overwritten without being freed (everything allocated is
 * then owned by *t: release with cmn_table_free()). Returns 0, or -1 with *t left empty (safe to
 * free) and, if err != NULL, a message in err (size errlen): the file cannot be opened or read,
 * holds a NUL byte, has no header or no data row, an empty or duplicate column name, an unclosed
 * quote, a header of numbers only (missing header), a cell that is not a finite number, or a ragged
 * row. Allocation failure exits (cmn_malloc).
 */
int cmn_table_read(const char *path, struct cmn_table *t, char *err, size_t errlen);
/** Free what *t owns and zero it. NULL accepted; an emptied table too. */
void cmn_table_free(struct cmn_table *t);
/** Index (0-based) of the column called `name`, or -1 if there is none. */
int cmn_table_column(const struct cmn_table *t, const char *name);
/**
 * Check that the header is exactly `names[0..ncols-1]`, in this order. Returns 0, or -1 with
 * "tab.csv:1: the header must be 't,value', got 'time,value'" in err (if err != NULL).
 */
int cmn_table_expect_columns(const struct cmn_table *t, int ncols, const char *const *names,
                             char *err, size_t errlen);
/**
 * Check that column `col` increases strictly from row to row (an interpolation abscissa).
 * Returns 0, or -1 with "tab.csv:5: column 1 ('t'): values must increase strictly, got 0.5 after
 * 0.5 (line 4)" in err (if err != NULL).
 */
int cmn_table_check_increasing(const struct cmn_table *t, int col, char *err, size_t errlen);

/**
 * Piecewise-linear interpolation through the n ≥ 1 nodes (x[k·stride], y[k·stride]), k < n,
 * with x strictly increasing (cmn_table_check_increasing): y(xq) on [x_0, x_{n-1}], exactly y_k
 * at a node, and the end value beyond either end (constant extrapolation). Units are those of y.
 * stride = 1 for plain arrays, ncols for two columns of a table. Returns NaN if xq is NaN or
 * n == 0. O(log n), no allocation.
 */
double cmn_interp_linear(size_t n, const double *x, const double *y, size_t stride, double xq);
/** cmn_interp_linear() on columns xcol (abscissa, strictly increasing) and ycol of a table. */
double cmn_table_interp(const struct cmn_table *t, int xcol, int ycol, double x);

/* ---------------------------------------------------------------------------------------------
 * Expressions (docs/case-files.md, "Expressions"): initial profiles such as "0.1*sin(4*pi*z)".
 *
 * Grammar: numbers (decimal or exponent notation), the caller's variables, the constant pi,
 * + − * / and ^ (power, right associative: 2^3^2 = 2^9; it binds tighter than a unary sign:
 * -x^2 = −(x²)), unary + and −, parentheses, and the functions of one argument sin cos tan asin
 * acos atan exp log sqrt abs tanh cosh sinh (C library semantics: log(−1) is NaN, 1/0 is inf;
 * callers check the values they need finite). Blanks are ignored between tokens. Compiled once
 * into a postfix program; evaluation allocates nothing for expressions of nesting depth ≤ 32 and
 * may run on several threads at once.
 * ------------------------------------------------------------------------------------------- */
struct cmn_expr;

/**
 * Compile `text` with the variables vars[0 .. nvars−1] (names of letters, digits and '_', e.g.
 * {"x", "y", "z"}). Returns NULL on a syntax error or an unknown name, with a message such as
 * "expression 'sin(x': expected ')' at column 6" or "expression 'y + 1': unknown name 'y'
 * (variables: x, pi; functions: ...) at column 1" in err (size errlen; err may be NULL).
 */
struct cmn_expr *cmn_expr_compile(const char *text, int nvars, const char *const *vars, char *err,
                                  size_t errlen);
/** Value of the expression with vals[i] for variable i (in the units the caller documents). */
double cmn_expr_eval(const struct cmn_expr *e, const double *vals);
/** Free a compiled expression (NULL accepted). */
void cmn_expr_free(struct cmn_expr *e);

/* ---------------------------------------------------------------------------------------------
 * Progress on stderr: "step 1200  t = 0.1234 s  dt = 1.2e-05 s  N = 40000  ETA 00:01:23"
 * ------------------------------------------------------------------------------------------- */
struct cmn_progress {
  double t_start, t_end; /**< simulated time span [s] */
  double wall_start;     /**< wall clock at start [s] */
  double wall_last;      /**< wall clock of the last report [s] */
  double interval;       /**< minimal wall seconds between reports (default 1) */
  int enabled;           /**< 0 silences reports */
};
/** Wall clock in seconds (monotonic). */
double cmn_wall_time(void);
void cmn_progress_start(struct cmn_progress *p, double t_start, double t_end);
/** Print a line if `interval` has passed since the last one, or if force != 0. */
void cmn_progress_report(struct cmn_progress *p, long step, double t, double dt, long count,
                         int force);
/**
 * The same for a task that is not a time integration (e.g. the SPH's initial repacking): prints
 * the printf-style text `fmt` followed by "  ETA hh:mm:ss", with `done` the progress on the scale
 * [t_start, t_end] given to cmn_progress_start() (e.g. iterations out of a total), if `interval`
 * has passed since the last line or if force != 0. The text is formatted only when printed.
 */
void cmn_progress_task(struct cmn_progress *p, double done, int force, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

#ifdef __cplusplus
}
#endif
#endif /* SABRE_COMMON_H */
