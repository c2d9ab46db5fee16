# R's Greenhouse–Geisser and Huynh–Feldt epsilons (stats::anova.mlm, its sphericity
# test's "test = 'Spherical'") and the exact CI of Cohen's d_z from R's noncentral t
# (stats::pt with ncp, the limits found by uniroot), on the within-subject reference data
# sets, written to within_r.json for tests/analysis/test_within_r.py.
#
#   Rscript tests/analysis/reference/within_r.R   (from the repository's root)
#
# Not a dependency: run once with Debian's r-base-core and r-cran-jsonlite; the output is
# committed.
library(jsonlite)
reference <- fromJSON("tests/analysis/reference/within_subject.json", simplifyVector = TRUE)

# anova.mlm prints the epsilons in its heading (4 digits; Huynh–Feldt not capped at 1)
# and uses them, capped, in the G-G and H-F p-values (full precision).
heading_number <- function(heading, label) {
  line <- grep(label, heading, value = TRUE)
  as.numeric(sub(".*:\\s*", "", line))
}

dz_ci <- function(d, level = 0.95) {
  n <- length(d)
  dz <- mean(d) / sd(d)
  t <- dz * sqrt(n)
  tail <- (1 - level) / 2
  f <- function(ncp, p) pt(t, n - 1, ncp) - p
  span <- 6 * sqrt(1 + t^2 / (2 * (n - 1))) + 1
  lower <- uniroot(f, c(t - span, t + span), p = 1 - tail, tol = 1e-12)$root
  upper <- uniroot(f, c(t - span, t + span), p = tail, tol = 1e-12)$root
  list(dz = dz, ci = c(lower, upper) / sqrt(n))
}

sets <- list()
for (k in seq_len(nrow(reference$datasets))) {
  scores <- as.data.frame(lapply(reference$datasets$scores[k, ], unlist))
  conditions <- sort(names(scores))
  scores <- scores[, conditions]
  fit <- lm(as.matrix(scores) ~ 1)
  sph <- anova(fit, X = ~1, test = "Spherical")
  pairs <- list()
  for (i in seq_along(conditions)) for (j in seq_along(conditions)) if (i < j) {
    d <- scores[[conditions[i]]] - scores[[conditions[j]]]
    pairs[[length(pairs) + 1]] <- c(list(a = conditions[i], b = conditions[j]), dz_ci(d))
  }
  heading <- attr(sph, "heading")
  sets[[k]] <- list(
    F = sph$F[1], p = sph$"Pr(>F)"[1],
    p_gg = sph$"G-G Pr"[1], p_hf = sph$"H-F Pr"[1],
    epsilon_gg = heading_number(heading, "Greenhouse-Geisser epsilon"),
    epsilon_hf = heading_number(heading, "Huynh-Feldt epsilon"),
    dz = pairs)
}
out <- list(software = R.version.string, within_subject = sets)
writeLines(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE),
           "tests/analysis/reference/within_r.json")
