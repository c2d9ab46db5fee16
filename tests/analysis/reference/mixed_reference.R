# Reference fits for tests/analysis/test_mixed_reference.py, by R's lme4 and ordinal.
# Run by make_mixed_reference.py (which writes the data sets first); Debian packages
# r-cran-lme4 and r-cran-ordinal, not project dependencies.
suppressPackageStartupMessages({
  library(lme4)
  library(ordinal)
  library(jsonlite)
})
args <- commandArgs(trailingOnly = TRUE)
folder <- args[1]

fixed <- function(estimates, errors) {
  lapply(seq_along(estimates), function(i) list(
    name = names(estimates)[i], estimate = unname(estimates[i]), se = unname(errors[i])))
}
sds <- function(model) {
  frame <- as.data.frame(VarCorr(model))
  frame <- frame[is.na(frame$var2), ]
  lapply(seq_len(nrow(frame)), function(i) list(
    group = frame$grp[i], column = frame$var1[i], sd = frame$sdcor[i]))
}
glmer_fit <- function(model) {
  list(
    fixed = fixed(fixef(model), sqrt(diag(as.matrix(vcov(model))))),
    random = sds(model),
    loglik = as.numeric(logLik(model))
  )
}

out <- list(
  software = list(
    R = paste(R.version$major, R.version$minor, sep = "."),
    lme4 = as.character(packageVersion("lme4")),
    ordinal = as.character(packageVersion("ordinal"))
  )
)
control <- glmerControl(optimizer = "bobyqa", optCtrl = list(maxfun = 1e5))

pairs <- read.csv(file.path(folder, "mixed_pairwise.csv"))
m1 <- glmer(first ~ 1 + x_b + x_c + x_d + (1 | participant) + (1 | item),
            data = pairs, family = binomial, control = control)
out$pairwise_intercepts <- glmer_fit(m1)
m2 <- glmer(first ~ 1 + x_b + x_c + x_d + (1 | participant) + (0 + x_b | participant) +
              (1 | item), data = pairs, family = binomial, control = control)
out$pairwise_slope <- glmer_fit(m2)

ratings <- read.csv(file.path(folder, "mixed_ratings.csv"))
ratings$rating <- factor(ratings$rating, ordered = TRUE)
ratings$condition <- factor(ratings$condition, levels = c("a", "b", "c"))
m3 <- clmm(rating ~ condition + (1 | participant) + (1 | item), data = ratings,
           link = "logit", nAGQ = 1)
s3 <- summary(m3)$coefficients
st <- VarCorr(m3)
out$ordinal <- list(
  fixed = lapply(rownames(s3), function(r) list(
    name = r, estimate = s3[r, "Estimate"], se = s3[r, "Std. Error"])),
  random = list(
    list(group = "participant", sd = attr(st$participant, "stddev")[[1]]),
    list(group = "item", sd = attr(st$item, "stddev")[[1]])),
  loglik = as.numeric(logLik(m3))
)

numeric <- read.csv(file.path(folder, "mixed_ratings.csv"))
numeric$condition <- factor(numeric$condition, levels = c("a", "b", "c"))
m4 <- lmer(rating ~ condition + (1 | participant) + (1 | item), data = numeric, REML = TRUE)
out$linear <- list(
  fixed = fixed(fixef(m4), sqrt(diag(as.matrix(vcov(m4))))),
  random = sds(m4),
  loglik = as.numeric(logLik(m4))
)

po <- read.csv(file.path(folder, "mixed_nonproportional.csv"))
po$rating <- factor(po$rating, ordered = TRUE)
po$condition <- factor(po$condition, levels = c("a", "b", "c"))
m5 <- clm(rating ~ condition, data = po, link = "logit")
test5 <- nominal_test(m5)
out$nominal <- list(
  statistic = test5$LRT[2], df = test5$Df[2], pvalue = test5[["Pr(>Chi)"]][2])
m6 <- clm(rating ~ condition, data = ratings, link = "logit")
test6 <- nominal_test(m6)
out$nominal_proportional <- list(
  statistic = test6$LRT[2], df = test6$Df[2], pvalue = test6[["Pr(>Chi)"]][2])

write(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE),
      file.path(folder, "mixed_reference.json"))
