/* sa_csv.h - CSV tables. Line 1 is "# units: name=unit, ..." (a comment line that
 * numpy/pandas/gnuplot skip with comment='#'), line 2 the column names, then rows of
 * numbers printed with 17 significant digits (round-trip exact). Written atomically. */
#ifndef SA_CSV_H
#define SA_CSV_H

typedef struct SaCsv SaCsv;

/* names/units [in]: ncols strings each. */
int sa_csv_open(const char *path, int ncols, const char *const *names, const char *const *units,
                SaCsv **out);
int sa_csv_row(SaCsv *t, const double *values); /* ncols values */
/* As sa_csv_row, but a NaN is written as an empty field ("no value here": numpy/pandas read
 * it as NaN, gnuplot skips the point); infinities are still refused. For tables whose columns
 * cover different ranges (a comparison of runs). */
int sa_csv_row_gaps(SaCsv *t, const double *values);
int sa_csv_commit(SaCsv **t);
void sa_csv_abort(SaCsv **t);

/* Reading a table back (ours, or any numeric CSV with one header line of names): lines
 * starting with '#' are comments, except that a "# units: name=unit, ..." line is kept; the
 * first other line gives the column names; every further non-empty line must have exactly
 * that many comma-separated numbers (an empty field reads as NaN). Anything else is
 * SA_ERR_INPUT naming path:line and the column. */
typedef struct SaCsvData SaCsvData;
int sa_csv_read(const char *path, SaCsvData **out); /* *out [owned] */
int sa_csv_data_nrows(const SaCsvData *d);
/* Column by name [borrowed], NULL if the table has no such column. */
const double *sa_csv_data_column(const SaCsvData *d, const char *name);
/* Unit of a column from the units line [borrowed]; NULL if the file or column has none. */
const char *sa_csv_data_unit(const SaCsvData *d, const char *name);
/* Comma-separated column names, for messages [borrowed]. */
const char *sa_csv_data_names(const SaCsvData *d);
void sa_csv_data_destroy(SaCsvData **d); /* accepts NULL; nulls the handle */

#endif
