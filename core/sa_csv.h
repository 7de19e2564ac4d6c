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
int sa_csv_commit(SaCsv **t);
void sa_csv_abort(SaCsv **t);

#endif
