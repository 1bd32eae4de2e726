/* Exact decimal-to-double conversion of short decimals, without strtod.
 * The particle reader parses millions of fields; glibc's strtod spends most
 * of its time in multiple-precision arithmetic on 17-digit fields.  This is
 * the same correctly rounded result (round to nearest, ties to even) by
 * 128-bit integer arithmetic, for the decimals it accepts; the rest go to
 * strtod (cli_parse_double). */
#ifndef CLI_DECIMAL_H
#define CLI_DECIMAL_H

/* s in the grammar [+-]digits[.digits][(e|E)[+-]digits] (at least one digit
 * before the exponent), at most 19 significant digits, and the value
 * m 10^e (m the significant digits as an integer) with -27 <= e <= 27:
 * *v = the double nearest to the value (bit-identical to strtod's), return 1.
 * Otherwise return 0 and leave *v alone. */
int cli_decimal(const char *s, double *v);

#endif
