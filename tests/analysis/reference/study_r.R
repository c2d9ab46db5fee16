# A study simulated and analysed by R, for the end-to-end golden test of the report
# (tests/analysis/test_golden_r_study.py): every number the report writes to
# results.json for its pairwise, rating, intelligibility and mixed-model sections, as R
# computes it. 16 participants, three conditions and six signed phrases: each
# participant judges every pair of conditions on every phrase (ties allowed), rates every
# phrase in every condition 1–5 and types what each clip said. A throwaway reference:
# Debian's R 4.2.2 with r-cran-lme4 1.1-31, r-cran-lmertest 3.1-3, r-cran-ordinal
# 2022.11-16 and r-cran-jsonlite, none of them project dependencies. Regenerate with:
#
#   apt-get install r-cran-lme4 r-cran-lmertest r-cran-ordinal r-cran-jsonlite
#   Rscript tests/analysis/reference/study_r.R tests/analysis/reference
#
# Writes study_r.csv (the tidy table) and study_r.json (R's numbers, in results.json's
# layout; list entries are matched by their names, not their order).
suppressPackageStartupMessages({
  library(lme4)
  library(lmerTest)
  library(ordinal)
  library(jsonlite)
})
folder <- commandArgs(trailingOnly = TRUE)[1]
set.seed(20261207)

LABELS <- c(ctl = "Constant timing", bayes = "Bayesian timing", mocap = "Motion capture")
STRENGTH <- c(ctl = 0, bayes = 0.5, mocap = 0.9)
CLARITY <- c(ctl = 0, bayes = 0.6, mocap = 1.1)
UNDERSTOOD <- c(ctl = 0.55, bayes = 0.7, mocap = 0.8)
PHRASES <- c("MY HOUSE", "TOY CAR", "GUITAR", "BIG DOG", "RED APPLE", "OLD FRIEND")
PARTICIPANTS <- sprintf("P%02d", 1:16)
THRESHOLDS <- c(-2.0, -0.7, 0.6, 2.0)

# --- The study --------------------------------------------------------------------------
bias <- setNames(rnorm(length(PARTICIPANTS), 0, 0.6), PARTICIPANTS)
hard <- setNames(rnorm(length(PHRASES), 0, 0.4), PHRASES)
row <- function(who, phrase, kind, a, b = "", chosen = "", question = "", rating = "",
                text = "", trial) {
  data.frame(participant = who, study = "rstudy", block = kind, trial = trial,
             item = phrase, kind = kind, condition_a = a, condition_b = b,
             condition_a_label = LABELS[a], condition_b_label = if (b == "") "" else LABELS[b],
             chosen = chosen, question = question, rating = rating, text = text,
             rt_ms = sample(800:4000, 1), flags = "",
             target = if (kind == "text") phrase else "", row.names = NULL)
}
rows <- list()
for (who in PARTICIPANTS) for (phrase in PHRASES) {
  for (pair in combn(names(LABELS), 2, simplify = FALSE)) {
    clips <- if (runif(1) < 0.5) pair else rev(pair)
    eta <- 0.25 + STRENGTH[clips[1]] - STRENGTH[clips[2]] + bias[who] + hard[phrase]
    chosen <- if (runif(1) < 0.08) "none" else if (runif(1) < plogis(eta)) clips[1] else clips[2]
    rows[[length(rows) + 1]] <- row(who, phrase, "pairwise", clips[1], clips[2], chosen,
                                    "most-natural", trial = paste(phrase, clips, collapse = "-"))
  }
  for (key in names(LABELS)) {
    latent <- CLARITY[key] + bias[who] + hard[phrase] + rlogis(1)
    rows[[length(rows) + 1]] <- row(who, phrase, "rating", key, question = "clarity",
                                    rating = 1 + findInterval(latent, THRESHOLDS),
                                    trial = paste(phrase, key, "rating"))
    wanted <- strsplit(phrase, " ")[[1]]
    kept <- wanted[runif(length(wanted)) < UNDERSTOOD[key]]
    rows[[length(rows) + 1]] <- row(who, phrase, "text", key,
                                    text = if (length(kept)) tolower(paste(kept, collapse = " ")) else "?",
                                    trial = paste(phrase, key, "text"))
  }
}
study <- do.call(rbind, rows)
write.csv(study, file.path(folder, "study_r.csv"), row.names = FALSE, na = "")

# --- Helpers ----------------------------------------------------------------------------
conditions <- sort(unname(LABELS))
pairs <- combn(conditions, 2, simplify = FALSE)
holm <- function(p) p.adjust(p, "holm")
quartiles <- function(x) unname(quantile(x, c(0.25, 0.75), type = 7))
binomial_test <- function(wins, losses) {
  n <- wins + losses
  test <- binom.test(wins, n)
  majority <- binom.test(max(wins, losses), n, alternative = "greater")
  list(a_wins = wins, b_wins = losses, nobs = n, statistic = wins / n, pvalue = test$p.value,
       pvalue_one_sided_majority = majority$p.value, ci = as.numeric(test$conf.int))
}
source(file.path(folder, "paired_tests.R"))  # signed_rank, dz_ci, paired (small_study.R's)
paired_t <- function(x, y) {
  r <- paired(x, y)
  list(statistic = r$t, df = r$df, pvalue = r$p, mean_difference = r$mean_difference,
       ci = r$ci, dz = r$dz, dz_ci = r$dz_ci, nobs = length(x))
}
wilcoxon <- function(x, y) {
  r <- signed_rank(x, y)
  list(statistic = r$V, pvalue = r$p, rank_biserial = r$r, nobs = r$n)
}
adjusted <- function(results, part = NULL) {
  get <- function(r) if (is.null(part)) r else r[[part]]
  p <- holm(sapply(results, function(r) get(r)$pvalue))
  for (i in seq_along(results)) {
    if (is.null(part)) results[[i]]$pvalue_adjusted <- p[i]
    else results[[i]][[part]]$pvalue_adjusted <- p[i]
  }
  results
}
# Paired t and signed-rank tests of every two conditions on participants × conditions.
comparisons <- function(scores, ...) {
  out <- lapply(pairs, function(p) {
    keep <- !is.na(scores[, p[1]]) & !is.na(scores[, p[2]])
    x <- scores[keep, p[1]]; y <- scores[keep, p[2]]
    list(a = p[1], b = p[2], ..., nobs = sum(keep), ttest = paired_t(x, y),
         wilcoxon = wilcoxon(x, y))
  })
  out
}
adjust_comparisons <- function(results) adjusted(adjusted(results, "ttest"), "wilcoxon")

# --- Pairwise judgements ----------------------------------------------------------------
pw <- study[study$kind == "pairwise", ]
pw$clip1 <- unname(LABELS[pw$condition_a]); pw$clip2 <- unname(LABELS[pw$condition_b])
pw$winner <- ifelse(pw$chosen == "none", "none", unname(LABELS[pw$chosen]))
decisive <- pw[pw$winner != "none", ]
shown <- table(c(pw$clip1, pw$clip2))
rate <- sapply(conditions, function(c) sapply(PARTICIPANTS, function(who) {
  mine <- pw[pw$participant == who, ]
  sum(mine$winner == c) / sum(mine$clip1 == c | mine$clip2 == c)
}))
condition_rates <- lapply(conditions, function(c) list(
  condition = c, shown = shown[[c]], chosen = sum(decisive$winner == c),
  win_rate = sum(decisive$winner == c) / shown[[c]],
  share = sum(decisive$winner == c) / nrow(decisive), mean_participant_rate = mean(rate[, c]),
  sem = sd(rate[, c]) / sqrt(nrow(rate)), nobs = nrow(rate)))
of_pair <- function(data, p) {
  data[(data$clip1 == p[1] & data$clip2 == p[2]) | (data$clip1 == p[2] & data$clip2 == p[1]), ]
}
pair_test <- function(data, p) {
  c(list(a = p[1], b = p[2], ties = sum(data$winner == "none")),
    binomial_test(sum(data$winner == p[1]), sum(data$winner == p[2])))
}
by_item <- unlist(lapply(sort(PHRASES), function(item) lapply(pairs, function(p)
  c(list(item = item), pair_test(of_pair(pw[pw$item == item, ], p), p)))), recursive = FALSE)

fit <- lm(rate ~ 1)
sphericity <- anova(fit, X = ~1, test = "Spherical")
epsilons <- stats:::sphericity(SSD(fit), X = ~1)
mauchly <- mauchly.test(fit, X = ~1)
long <- data.frame(score = as.vector(rate), participant = factor(rep(rownames(rate), ncol(rate))),
                   condition = factor(rep(colnames(rate), each = nrow(rate))))
within <- summary(aov(score ~ condition + Error(participant / condition), long))
squares <- within[["Error: participant:condition"]][[1]][["Sum Sq"]]
friedman <- friedman.test(rate)

counts <- do.call(rbind, lapply(pairs, function(p) {
  rows <- of_pair(decisive, p)
  data.frame(a = p[1], b = p[2], a_wins = sum(rows$winner == p[1]), b_wins = sum(rows$winner == p[2]))
}))
for (c in conditions[-1]) counts[[c]] <- (counts$a == c) - (counts$b == c)
bt <- glm(cbind(a_wins, b_wins) ~ 0 + ., family = binomial,
          data = counts[, c("a_wins", "b_wins", conditions[-1])])
wald <- confint.default(bt)
strengths <- c(list(list(condition = conditions[1], log_worth = 0, se = 0, ci = c(0, 0), worth = 1)),
  lapply(seq_along(conditions[-1]), function(i) list(
    condition = conditions[i + 1], log_worth = unname(coef(bt)[i]),
    se = unname(sqrt(diag(vcov(bt)))[i]), ci = unname(wald[i, ]), worth = exp(unname(coef(bt)[i])))))
clip1 <- sum(decisive$winner == decisive$clip1)
position <- binom.test(clip1, nrow(decisive))

pairwise <- list(
  conditions = condition_rates,
  pairs = adjusted(lapply(pairs, function(p) pair_test(of_pair(pw, p), p))),
  items = adjusted(by_item),
  rm_anova = list(statistic = sphericity$F[1], df_num = sphericity$`num Df`[1],
                  df_den = sphericity$`den Df`[1], pvalue = sphericity$`Pr(>F)`[1],
                  epsilon_gg = epsilons$GG.eps, pvalue_gg = sphericity$`G-G Pr`[1],
                  epsilon_hf = epsilons$HF.eps, pvalue_hf = sphericity$`H-F Pr`[1],
                  eta_p2 = squares[1] / sum(squares), mauchly_w = unname(mauchly$statistic),
                  mauchly_pvalue = mauchly$p.value, nobs = nrow(rate)),
  posthoc = adjusted(lapply(pairs, function(p) c(list(a = p[1], b = p[2]),
                                                 paired_t(rate[, p[1]], rate[, p[2]])))),
  wilcoxon = adjusted(lapply(pairs, function(p) c(list(a = p[1], b = p[2]),
                                                  wilcoxon(rate[, p[1]], rate[, p[2]])))),
  friedman = list(statistic = unname(friedman$statistic), df = unname(friedman$parameter),
                  pvalue = friedman$p.value, nobs = nrow(rate),
                  kendall_w = unname(friedman$statistic) / (nrow(rate) * (ncol(rate) - 1))),
  bradley_terry = list(strengths = strengths, nobs = nrow(decisive),
                       log_likelihood = as.numeric(logLik(bt))),
  position_bias = list(clip1 = clip1, clip2 = nrow(decisive) - clip1, nobs = nrow(decisive),
                       statistic = clip1 / nrow(decisive), pvalue = position$p.value,
                       ci = as.numeric(position$conf.int)),
  ties = sum(pw$winner == "none"), judgements = nrow(pw), participants = length(PARTICIPANTS))

# --- Ratings and intelligibility ------------------------------------------------------------
rt <- study[study$kind == "rating", ]
rt$condition <- unname(LABELS[rt$condition_a]); rt$rating <- as.numeric(rt$rating)
tx <- study[study$kind == "text", ]
tx$condition <- unname(LABELS[tx$condition_a])
# Whole-word accuracy: the share of the target's words found in the answer, each used once
# (no answer here is a misspelling, so the report's fuzzy matching finds nothing more).
tx$score <- mapply(function(answer, target) {
  given <- strsplit(toupper(answer), "[^A-Z0-9']+")[[1]]
  wanted <- strsplit(toupper(target), "[^A-Z0-9']+")[[1]]
  found <- 0
  for (w in wanted) if (w %in% given) { given <- given[-match(w, given)]; found <- found + 1 }
  found / length(wanted)
}, tx$text, tx$target)

wide <- function(rows, value) {
  sapply(conditions, function(c) sapply(PARTICIPANTS, function(who)
    mean(rows[[value]][rows$participant == who & rows$condition == c])))
}
cells <- expand.grid(condition = conditions, item = sort(PHRASES), stringsAsFactors = FALSE)
ratings <- lapply(seq_len(nrow(cells)), function(i) {
  r <- rt$rating[rt$item == cells$item[i] & rt$condition == cells$condition[i]]
  list(question = "clarity", item = cells$item[i], condition = cells$condition[i], n = length(r),
       median = median(r), q1 = quartiles(r)[1], q3 = quartiles(r)[2], mean = mean(r), sd = sd(r),
       pct_ge3 = 100 * mean(r >= 3), pct_ge4 = 100 * mean(r >= 4))
})
rating_comparisons <- adjust_comparisons(unlist(lapply(sort(PHRASES), function(item)
  comparisons(wide(rt[rt$item == item, ], "rating"), item = item, question = "clarity")),
  recursive = FALSE))
across <- function(rows, value, measure) {
  means <- wide(rows, value)
  list(conditions = lapply(conditions, function(c) {
    m <- means[, c]; s <- rows[[value]][rows$condition == c]
    list(measure = measure, condition = c, n = length(s), nobs = length(m),
         items = length(unique(rows$item)), mean = mean(m), sd = sd(m),
         sem = sd(m) / sqrt(length(m)), ci = as.numeric(t.test(m)$conf.int), median = median(s),
         q1 = quartiles(s)[1], q3 = quartiles(s)[2])
  }), comparisons = adjust_comparisons(comparisons(means, measure = measure)))
}
rating_across <- across(rt, "rating", "clarity")
text_across <- across(tx, "score", "accuracy")
intelligibility <- lapply(seq_len(nrow(cells)), function(i) {
  s <- tx$score[tx$item == cells$item[i] & tx$condition == cells$condition[i]]
  list(condition = cells$condition[i], item = cells$item[i], n = length(s),
       mean_accuracy = mean(s), sem = sd(s) / sqrt(length(s)))
})

# --- Mixed models ---------------------------------------------------------------------------
z_row <- function(name, estimate, se) {
  list(name = name, estimate = estimate, se = se, statistic = estimate / se,
       pvalue = 2 * pnorm(-abs(estimate / se)), ci = estimate + c(-1, 1) * qnorm(0.975) * se)
}
# Every two conditions, the later (alphabetically) minus the earlier, Holm-adjusted.
wald_contrasts <- function(beta, cov) {
  out <- lapply(pairs, function(p) {
    l <- setNames(numeric(length(conditions)), conditions)
    l[p[2]] <- 1; l[p[1]] <- -1
    l <- l[-1]
    row <- z_row("", sum(l * beta), sqrt(drop(t(l) %*% cov %*% l)))
    c(list(a = p[2], b = p[1]), row[-1])
  })
  adjusted(out)
}
wald <- function(beta, cov) {
  statistic <- drop(t(beta) %*% solve(cov) %*% beta)
  list(statistic = statistic, df = length(beta), pvalue = pchisq(statistic, length(beta), lower.tail = FALSE))
}
random_sds <- function(sds, levels) {
  lapply(names(sds), function(g) list(name = g, sd = sds[[g]], variance = sds[[g]]^2,
                                      levels = levels[[g]]))
}
levels_of <- function(data) list(participant = length(unique(data$participant)),
                                 item = length(unique(data$item)))

decisive$first <- as.numeric(decisive$winner == decisive$clip1)
for (c in conditions[-1]) decisive[[c]] <- (decisive$clip1 == c) - (decisive$clip2 == c)
names(decisive)[match(conditions[-1], names(decisive))] <- paste0("x", seq_along(conditions[-1]))
glmm <- glmer(first ~ 1 + x1 + x2 + (1 | participant) + (1 | item), data = decisive,
              family = binomial, control = glmerControl(tolPwrss = 1e-13))
beta <- fixef(glmm)[-1]; cov <- as.matrix(vcov(glmm))[-1, -1]
se <- sqrt(diag(as.matrix(vcov(glmm))))
frame <- as.data.frame(VarCorr(glmm))
mixed_pairwise <- c(list(
  effects = lapply(seq_along(beta), function(i) z_row(conditions[i + 1], unname(beta[i]), unname(se[i + 1]))),
  contrasts = wald_contrasts(beta, cov),
  random = random_sds(setNames(as.list(frame$sdcor), frame$grp), levels_of(decisive)),
  position = z_row("position", unname(fixef(glmm)[1]), unname(se[1])),
  loglik = as.numeric(logLik(glmm)), aic = AIC(glmm), nobs = nrow(decisive),
  participants = length(unique(decisive$participant)), items = length(unique(decisive$item))),
  wald(beta, cov))

rt$condition_f <- factor(rt$condition, levels = conditions)
rt$rating_f <- factor(rt$rating, ordered = TRUE)
cumulative <- clmm(rating_f ~ condition_f + (1 | participant) + (1 | item), data = rt)
coefs <- summary(cumulative)$coefficients
effect_names <- paste0("condition_f", conditions[-1])
beta <- coefs[effect_names, "Estimate"]
cov <- vcov(cumulative)[effect_names, effect_names]
cuts <- names(cumulative$alpha)
nominal <- nominal_test(clm(rating_f ~ condition_f, data = rt))
sds <- lapply(VarCorr(cumulative), function(v) attr(v, "stddev")[[1]])
mixed_ordinal <- c(list(
  question = "clarity",
  effects = lapply(seq_along(beta), function(i)
    z_row(conditions[i + 1], unname(beta[i]), coefs[effect_names[i], "Std. Error"])),
  thresholds = lapply(cuts, function(k) z_row(k, coefs[k, "Estimate"], coefs[k, "Std. Error"])),
  contrasts = wald_contrasts(beta, cov),
  random = random_sds(sds, levels_of(rt)),
  proportional_odds = list(statistic = nominal$LRT[2], df = nominal$Df[2],
                           pvalue = nominal$`Pr(>Chi)`[2]),
  loglik = as.numeric(logLik(cumulative)), aic = AIC(cumulative), nobs = nrow(rt),
  participants = length(unique(rt$participant)), items = length(unique(rt$item))),
  wald(beta, cov))

linear <- lmerTest::lmer(rating ~ condition_f + (1 | participant) + (1 | item), data = rt)
table <- summary(linear)$coefficients
t_row <- function(name, estimate, se, df) {
  list(name = name, estimate = estimate, se = se, df = df, statistic = estimate / se,
       pvalue = 2 * pt(-abs(estimate / se), df), ci = estimate + c(-1, 1) * qt(0.975, df) * se)
}
linear_contrasts <- adjusted(lapply(pairs, function(p) {
  l <- setNames(numeric(length(conditions)), conditions)
  l[p[2]] <- 1; l[p[1]] <- -1
  test <- contest(linear, c(0, l[-1]), joint = FALSE)
  c(list(a = p[2], b = p[1]), t_row("", test$Estimate, test$`Std. Error`, test$df)[-1])
}))
f <- anova(linear)
ml <- update(linear, REML = FALSE)
null <- update(ml, . ~ 1 + (1 | participant) + (1 | item))
lr <- anova(null, ml)
profile <- confint(linear, parm = "theta_", method = "profile", oldNames = FALSE)
frame <- as.data.frame(VarCorr(linear))
groups <- frame$grp[frame$grp != "Residual"]
random <- random_sds(setNames(as.list(frame$sdcor[frame$grp != "Residual"]), groups), levels_of(rt))
for (i in seq_along(random)) random[[i]]$ci <- unname(profile[paste0("sd_(Intercept)|", random[[i]]$name), ])
mixed_linear <- list(
  question = "clarity",
  effects = lapply(effect_names, function(k)
    t_row(sub("condition_f", "", k), table[k, "Estimate"], table[k, "Std. Error"], table[k, "df"])),
  contrasts = linear_contrasts, random = random,
  statistic = f$`F value`, df = f$NumDF, den_df = f$DenDF, pvalue = f$`Pr(>F)`,
  likelihood_ratio = list(statistic = lr$Chisq[2], df = lr$Df[2], pvalue = lr$`Pr(>Chisq)`[2],
                          loglik_full = as.numeric(logLik(ml)),
                          loglik_reduced = as.numeric(logLik(null))),
  residual_sd = sigma(linear), residual_sd_ci = unname(profile["sigma", ]),
  loglik = as.numeric(logLik(linear)), aic = AIC(linear), nobs = nrow(rt),
  participants = length(unique(rt$participant)), items = length(unique(rt$item)))

out <- list(
  software = list(R = R.version.string, lme4 = as.character(packageVersion("lme4")),
                  lmerTest = as.character(packageVersion("lmerTest")),
                  ordinal = as.character(packageVersion("ordinal"))),
  pairwise = pairwise, ratings = ratings, rating_comparisons = rating_comparisons,
  rating_conditions = rating_across$conditions,
  rating_condition_comparisons = rating_across$comparisons,
  intelligibility = intelligibility, intelligibility_conditions = text_across$conditions,
  intelligibility_comparisons = text_across$comparisons,
  mixed_models = list(pairwise = mixed_pairwise, ordinal = list(mixed_ordinal),
                      linear = list(mixed_linear)))
write(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE), file.path(folder, "study_r.json"))
