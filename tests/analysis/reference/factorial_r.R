# A two-way within-subject design (16 subjects × A with 2 levels × B with 3), simulated
# here, and R's repeated-measures ANOVA of it: F and p per effect from
# aov(y ~ A * B + Error(subject / (A * B))), and per effect the Greenhouse–Geisser and
# Huynh–Feldt corrected p-values and Mauchly's test from anova.mlm / mauchly.test with
# idata and the effect's M and X, for tests/analysis/test_factorial_anova.py (issue 56,
# item 8). Not a dependency: run once with Debian's r-base-core and r-cran-jsonlite, from
# the repository's root:
#
#   Rscript tests/analysis/reference/factorial_r.R
suppressPackageStartupMessages(library(jsonlite))
set.seed(20261206)
n <- 16
idata <- expand.grid(B = factor(c("b1", "b2", "b3")), A = factor(c("a1", "a2")))
idata <- idata[, c("A", "B")]
cells <- paste(idata$A, idata$B, sep = ".")
effect <- c(0, 0.3, 0.5, 0.2, 0.9, 0.6)
subject <- rnorm(n, 0, 1)
# Unequal variances and correlations across cells, so sphericity is at stake for B.
noise <- matrix(rnorm(n * 6), n, 6) %*% diag(c(0.5, 0.6, 1.2, 0.5, 0.7, 1.4))
Y <- outer(subject, rep(1, 6)) + matrix(effect, n, 6, byrow = TRUE) + noise
colnames(Y) <- cells
long <- data.frame(subject = factor(rep(seq_len(n), 6)), A = rep(idata$A, each = n),
                   B = rep(idata$B, each = n), y = as.vector(Y))
write.csv(long, "tests/analysis/reference/factorial.csv", row.names = FALSE)

strata <- summary(aov(y ~ A * B + Error(subject / (A * B)), data = long))
row_of <- function(stratum) {
  t <- strata[[stratum]][[1]]
  list(F = t[1, "F value"], df_num = t[1, "Df"], df_den = t[2, "Df"], p = t[1, "Pr(>F)"])
}
fit <- lm(Y ~ 1)
corrected <- function(M, X) {
  s <- anova(fit, M = M, X = X, idata = idata, test = "Spherical")
  m <- mauchly.test(fit, M = M, X = X, idata = idata)
  list(p_gg = s$"G-G Pr"[1], p_hf = s$"H-F Pr"[1], mauchly_w = unname(m$statistic),
       mauchly_p = m$p.value)
}
out <- list(
  software = R.version.string,
  A = c(row_of("Error: subject:A"), corrected(~A, ~1)),
  B = c(row_of("Error: subject:B"), corrected(~A + B, ~A)),
  `A:B` = c(row_of("Error: subject:A:B"), corrected(~A * B, ~A + B))
)
writeLines(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE),
           "tests/analysis/reference/factorial_r.json")
