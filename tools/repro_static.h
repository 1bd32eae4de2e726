/* The Table III rows of paper 004 for `mfstab reproduce` (tools/repro_static.c). */
#ifndef MFSTAB_REPRO_STATIC_H
#define MFSTAB_REPRO_STATIC_H

/* Write the coarse refinement studies of the beam and the plate into outdir
 * (static_table3_beam.csv, static_table3_plate.csv) and call row() once per
 * cell of Table III (method x {beam, plate} x {energy, L2}). */
void repro_static_rows(const char *outdir,
                       void (*row)(const char *artifact, const char *paper, double ours,
                                   const char *status));

#endif
