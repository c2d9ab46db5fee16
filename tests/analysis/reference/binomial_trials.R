# A crossed binomial data set with trials (words right out of words signed, per
# participant, item and condition), simulated and fitted here by lme4's
# glmer(cbind(correct, trials - correct) ~ condition + (1 | participant) + (1 | item))
# with its PIRLS run to convergence (tolPwrss = 1e-13), for
# tests/analysis/test_mixed_binomial.py (issue 56, item 8). Not a dependency: run once
# with Debian's r-cran-lme4 and r-cran-jsonlite, from the repository's root:
#
#   Rscript tests/analysis/reference/binomial_trials.R
suppressPackageStartupMessages({
  library(lme4)
  library(jsonlite)
})
set.seed(20261206)
participants <- sprintf("P%02d", 1:30)
items <- sprintf("I%02d", 1:12)
d <- expand.grid(participant = participants, item = items, condition = c("off", "on"),
                 stringsAsFactors = FALSE)
u <- setNames(rnorm(length(participants), 0, 0.7), participants)
w <- setNames(rnorm(length(items), 0, 0.4), items)
eta <- 0.3 + 0.5 * (d$condition == "on") + u[d$participant] + w[d$item]
d$trials <- sample(3:9, nrow(d), replace = TRUE)
d$correct <- rbinom(nrow(d), d$trials, plogis(eta))
write.csv(d, "tests/analysis/reference/binomial_trials.csv", row.names = FALSE)
m <- glmer(cbind(correct, trials - correct) ~ condition + (1 | participant) + (1 | item),
           data = d, family = binomial,
           control = glmerControl(optimizer = "bobyqa", tolPwrss = 1e-13))
vc <- as.data.frame(VarCorr(m))
out <- list(
  software = list(R = R.version.string, lme4 = as.character(packageVersion("lme4"))),
  fixed = as.list(fixef(m)),
  se = as.list(sqrt(diag(as.matrix(vcov(m))))),
  sd = setNames(as.list(vc$sdcor), vc$grp),
  loglik = as.numeric(logLik(m))
)
writeLines(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE),
           "tests/analysis/reference/binomial_trials.json")
