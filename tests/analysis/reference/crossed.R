# Crossed designs simulated and fitted by R, for tests/analysis/test_mixed_crossed.py.
#
# Each of 100 sets is P participants × I items, each participant seeing every item in
# both conditions (binary, Likert and numeric responses) and judging every pair of three
# conditions once per item (forced choices). Sizes cycle through 20 × 10, 8 × 4 and
# 12 × 6; the participant and item SDs through seven pairs, true zeros and unequal SDs
# among them. R fits them with lme4 (glmer with tolPwrss = 1e-12, lmer by REML and ML),
# lmerTest (Satterthwaite df, anova) and ordinal (clmm). A throwaway reference: Debian's
# r-cran-lme4 1.1-31, r-cran-lmertest 3.1-3, r-cran-ordinal 2022.11-16 and
# r-cran-jsonlite, none of them project dependencies. Regenerate with:
#
#   apt-get install r-cran-lme4 r-cran-lmertest r-cran-ordinal r-cran-jsonlite
#   Rscript tests/analysis/reference/crossed.R tests/analysis/reference
suppressPackageStartupMessages({
  library(lme4)
  library(lmerTest)
  library(ordinal)
  library(jsonlite)
})
folder <- commandArgs(trailingOnly = TRUE)[1]
SETS <- 100
SIZES <- list(c(20, 10), c(8, 4), c(12, 6))
SDS <- list(c(0.5, 0.3), c(0, 0), c(0.5, 0), c(0, 0.5), c(1.2, 0.2), c(0.2, 1.0), c(1, 1))
THRESHOLDS <- c(-2.0, -0.7, 0.6, 2.0)
STRENGTH <- c(a = 0, b = 0.6, c = 0.3)

simulate <- function(s) {
  set.seed(20261203 + s)
  size <- SIZES[[(s - 1) %% 3 + 1]]
  sd <- SDS[[((s - 1) %/% 3) %% 7 + 1]]
  np <- size[1]; ni <- size[2]
  bp <- rnorm(np, 0, sd[1]); bi <- rnorm(ni, 0, sd[2])
  # Half the sets give participants their own condition effects (SD 0.4, r = 0.5 with
  # their intercepts), for the correlated-slope fits.
  slope_sd <- if (s %% 2 == 0) 0.4 else 0
  slope <- 0.5 * slope_sd / max(sd[1], 1e-9) * bp * (sd[1] > 0) +
    rnorm(np, 0, slope_sd * sqrt(0.75))
  within <- expand.grid(condition = c("off", "on"), item = seq_len(ni),
                        participant = seq_len(np), stringsAsFactors = FALSE)
  x <- as.numeric(within$condition == "on")
  u <- bp[within$participant] + bi[within$item]
  within$binary <- rbinom(nrow(within), 1, plogis(0.2 + 0.5 * x + u))
  latent <- 0.5 * x + u + rlogis(nrow(within))
  within$rating <- 1 + findInterval(latent, THRESHOLDS)
  within$numeric <- 3 + 0.4 * x + u + slope[within$participant] * x + rnorm(nrow(within))
  pairs <- expand.grid(pair = 1:3, item = seq_len(ni), participant = seq_len(np))
  first <- c("a", "a", "b")[pairs$pair]; second <- c("b", "c", "c")[pairs$pair]
  swap <- runif(nrow(pairs)) < 0.5
  pairs$clip1 <- ifelse(swap, second, first); pairs$clip2 <- ifelse(swap, first, second)
  pairs$x_b <- (pairs$clip1 == "b") - (pairs$clip2 == "b")
  pairs$x_c <- (pairs$clip1 == "c") - (pairs$clip2 == "c")
  eta <- 0.2 + STRENGTH[pairs$clip1] - STRENGTH[pairs$clip2] +
    bp[pairs$participant] + bi[pairs$item]
  pairs$first <- rbinom(nrow(pairs), 1, plogis(eta))
  pairs$pair <- NULL
  within$participant <- sprintf("P%02d", within$participant)
  within$item <- sprintf("I%02d", within$item)
  pairs$participant <- sprintf("P%02d", pairs$participant)
  pairs$item <- sprintf("I%02d", pairs$item)
  list(within = cbind(set = s, within), pairs = cbind(set = s, pairs),
       truth = list(participants = np, items = ni, sd_participant = sd[1], sd_item = sd[2],
                    slope_sd = slope_sd))
}

quietly <- function(expr) {
  messages <- character()
  value <- withCallingHandlers(expr,
    warning = function(w) { messages <<- c(messages, conditionMessage(w)); invokeRestart("muffleWarning") },
    message = function(m) { messages <<- c(messages, conditionMessage(m)); invokeRestart("muffleMessage") })
  list(value = value, messages = messages)
}

lme4_fit <- function(model, messages) {
  frame <- as.data.frame(VarCorr(model))
  list(
    fixed = as.list(fixef(model)),
    se = as.list(sqrt(diag(as.matrix(vcov(model))))),
    sd = setNames(as.list(frame$sdcor), ifelse(is.na(frame$var2),
      paste(frame$grp, frame$var1), paste(frame$grp, frame$var1, frame$var2))),
    theta = unname(getME(model, "theta")),
    loglik = as.numeric(logLik(model)),
    singular = isSingular(model),
    messages = messages
  )
}

glmm <- function(formula, data) {
  run <- quietly(glmer(formula, data = data, family = binomial,
                       control = glmerControl(tolPwrss = 1e-12)))
  lme4_fit(run$value, run$messages)
}

lmm <- function(formula, data, reml) {
  run <- quietly(lmerTest::lmer(formula, data = data, REML = reml))
  out <- lme4_fit(run$value, run$messages)
  out$residual_sd <- sigma(run$value)
  table <- summary(run$value)$coefficients
  out$satterthwaite <- list(df = as.list(table[, "df"]), pvalue = as.list(table[, "Pr(>|t|)"]),
                            t = as.list(table[, "t value"]))
  f <- anova(run$value)
  out$anova <- list(F = f[["F value"]], df_num = f[["NumDF"]], df_den = f[["DenDF"]],
                    pvalue = f[["Pr(>F)"]])
  list(fit = out, model = run$value)
}

sets <- lapply(seq_len(SETS), simulate)
within <- do.call(rbind, lapply(sets, `[[`, "within"))
pairs <- do.call(rbind, lapply(sets, `[[`, "pairs"))
write.csv(within, gzfile(file.path(folder, "crossed_within.csv.gz")), row.names = FALSE)
write.csv(pairs, gzfile(file.path(folder, "crossed_pairs.csv.gz")), row.names = FALSE)

fits <- lapply(seq_len(SETS), function(s) {
  w <- within[within$set == s, ]
  w$condition <- factor(w$condition, levels = c("off", "on"))
  p <- pairs[pairs$set == s, ]
  out <- list(set = s, truth = sets[[s]]$truth)
  out$binary <- glmm(binary ~ condition + (1 | participant) + (1 | item), w)
  out$pairwise <- glmm(first ~ 1 + x_b + x_c + (1 | participant) + (1 | item), p)
  w$rating_f <- factor(w$rating, ordered = TRUE)
  run <- quietly(clmm(rating_f ~ condition + (1 | participant) + (1 | item), data = w))
  m <- run$value
  st <- VarCorr(m)
  out$ordinal <- list(
    fixed = as.list(coef(m)),
    se = as.list(summary(m)$coefficients[, "Std. Error"]),
    sd = list(participant = attr(st$participant, "stddev")[[1]],
              item = attr(st$item, "stddev")[[1]]),
    loglik = as.numeric(logLik(m)),
    messages = run$messages
  )
  reml <- lmm(numeric ~ condition + (1 | participant) + (1 | item), w, TRUE)
  ml <- lmm(numeric ~ condition + (1 | participant) + (1 | item), w, FALSE)
  out$reml <- reml$fit
  out$ml <- ml$fit
  null <- lmm(numeric ~ 1 + (1 | participant) + (1 | item), w, FALSE)
  lr <- anova(null$model, ml$model)
  out$lr <- list(statistic = lr$Chisq[2], df = lr$Df[2], pvalue = lr[["Pr(>Chisq)"]][2],
                 loglik_null = as.numeric(logLik(null$model)))
  slopes <- lmm(numeric ~ condition + (condition | participant) + (1 | item), w, TRUE)
  out$slopes <- slopes$fit
  if (s <= 20) {
    ci <- quietly(tryCatch(confint(reml$model, method = "profile", oldNames = FALSE),
                           error = function(e) NULL))$value
    if (!is.null(ci)) {
      out$reml$profile <- setNames(lapply(seq_len(nrow(ci)), function(i) unname(ci[i, ])),
                                   rownames(ci))
    }
  }
  out
})

software <- list(
  R = paste(R.version$major, R.version$minor, sep = "."),
  lme4 = as.character(packageVersion("lme4")),
  lmerTest = as.character(packageVersion("lmerTest")),
  ordinal = as.character(packageVersion("ordinal"))
)
write(toJSON(list(software = software, sets = fits), auto_unbox = TRUE, digits = NA,
             null = "null", na = "null"),
      file.path(folder, "crossed_fits.json"))
