#pragma once
// The two-sided tail of Student's t distribution, for compare --test where a
// variance is estimated from few degrees of freedom (the spread of a handful of
// independent images: vkrt stack). Written from the definitions: the tail is a
// regularized incomplete beta function (Abramowitz and Stegun 26.7.1), evaluated
// by its continued fraction (A&S 26.5.8) with the modified Lentz algorithm.

namespace vkrt {

// I_x(a, b), the regularized incomplete beta function, for a, b > 0 and x in [0, 1].
double incomplete_beta(double a, double b, double x);

// P(|T| >= |t|) for T of Student's t distribution with `dof` degrees of freedom
// (any real dof > 0; infinite: the standard normal's erfc(|t| / sqrt 2)).
double two_sided_t_p(double t, double dof);

}  // namespace vkrt
