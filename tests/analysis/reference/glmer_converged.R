# glmer's standard errors with its PIRLS run to convergence, for
# tests/analysis/test_mixed_reference.py: the two pairwise models of mixed_reference.R
# refitted with glmerControl(tolPwrss = 1e-13). With the default tolPwrss = 1e-7 glmer's
# PIRLS stops on a relative change in the penalized deviance and takes log det L from the
# iterate before the last, so the deviance whose finite-difference Hessian gives vcov()
# lags the Laplace approximation and the standard errors move by 0.1–1.3 % (issue 56).
# Not a dependency: run once with Debian's r-cran-lme4 and r-cran-jsonlite, from the
# repository's root:
#
#   Rscript tests/analysis/reference/glmer_converged.R
suppressPackageStartupMessages({
  library(lme4)
  library(jsonlite)
})
pairs <- read.csv("tests/analysis/reference/mixed_pairwise.csv")
fit <- function(formula, tol) {
  control <- glmerControl(optimizer = "bobyqa", optCtrl = list(maxfun = 1e5), tolPwrss = tol)
  model <- glmer(formula, data = pairs, family = binomial, control = control)
  list(se = as.list(sqrt(diag(as.matrix(vcov(model))))),
       estimate = as.list(fixef(model)), loglik = as.numeric(logLik(model)))
}
formulas <- list(
  pairwise_intercepts = first ~ 1 + x_b + x_c + x_d + (1 | participant) + (1 | item),
  pairwise_slope = first ~ 1 + x_b + x_c + x_d + (1 | participant) +
    (0 + x_b | participant) + (1 | item)
)
out <- list(software = list(R = R.version.string, lme4 = as.character(packageVersion("lme4"))))
for (name in names(formulas)) {
  out[[name]] <- list(converged = fit(formulas[[name]], 1e-13),
                      default = fit(formulas[[name]], 1e-7))
}
writeLines(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE),
           "tests/analysis/reference/glmer_converged.json")
