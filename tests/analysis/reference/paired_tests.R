# The paired tests the golden report tests compare with, as R computes them; sourced by
# small_study.R and study_r.R (throwaway references: base R only).

# R's own paired signed-rank test (wilcox.test's defaults: V = the positive differences'
# rank sum; exact p for n < 50 without ties or zeros, else the normal approximation with
# continuity correction), on differences rounded as the analysis rounds them.
signed_rank <- function(x, y) {
  # Means of fractions (1/3 + 2/3 …) differ in the last bits; equal values must tie.
  diff <- round(x - y, 12)
  nonzero <- diff[diff != 0]
  r <- rank(abs(nonzero))
  plus <- sum(r[nonzero > 0]); minus <- sum(r[nonzero < 0])
  test <- suppressWarnings(wilcox.test(diff))
  exact <- !grepl("continuity", test$method)
  list(V = unname(test$statistic), p = test$p.value, r = (plus - minus) / (plus + minus),
       n = length(x), method = if (exact) "exact" else "normal approximation, continuity-corrected")
}
# The exact 95 % CI of d_z: the noncentralities at which the observed t is the 97.5 %
# and 2.5 % point of R's noncentral t (Steiger & Fouladi 1997), over sqrt(n).
dz_ci <- function(dz, n) {
  t <- dz * sqrt(n)
  f <- function(ncp, p) pt(t, n - 1, ncp) - p
  span <- 6 * sqrt(1 + t^2 / (2 * (n - 1))) + 1
  limit <- function(p) uniroot(f, c(t - span, t + span), p = p, tol = 1e-12)$root
  suppressWarnings(c(limit(0.975), limit(0.025)) / sqrt(n))
}
paired <- function(x, y) {
  t <- t.test(x, y, paired = TRUE)
  dz <- mean(x - y) / sd(x - y)
  list(t = unname(t$statistic), df = unname(t$parameter), p = t$p.value,
       mean_difference = unname(t$estimate), ci = as.numeric(t$conf.int),
       dz = dz, dz_ci = dz_ci(dz, length(x)))
}
