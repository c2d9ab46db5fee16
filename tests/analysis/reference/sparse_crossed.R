# A sparse crossed design shaped like lme4's InstEval (each participant rates a few of
# many items), simulated and fitted by R for tests/analysis/test_mixed_sparse.py: the
# fits whose random-effects system is too wide to eliminate participants first and is
# factored sparse (analysis.mixed.cholesky). 150 participants each rate 24 of 400 items,
# the condition drawn per rating, and make 24 forced choices among three conditions on
# random items. R fits lmer by REML (lmerTest: Satterthwaite df, anova; profile CIs of the
# SDs) and ML (the LR test), clmm, and glmer with tolPwrss = 1e-12. A throwaway
# reference: Debian's r-cran-lme4 1.1-31, r-cran-lmertest 3.1-3, r-cran-ordinal
# 2022.11-16 and r-cran-jsonlite, none of them project dependencies. Regenerate with:
#
#   apt-get install r-cran-lme4 r-cran-lmertest r-cran-ordinal r-cran-jsonlite
#   Rscript tests/analysis/reference/sparse_crossed.R tests/analysis/reference
suppressPackageStartupMessages({
  library(lme4)
  library(lmerTest)
  library(ordinal)
  library(jsonlite)
})
folder <- commandArgs(trailingOnly = TRUE)[1]
set.seed(20261206)
PARTICIPANTS <- 150; ITEMS <- 400; EACH <- 24
THRESHOLDS <- c(-2.0, -0.7, 0.6, 2.0)
STRENGTH <- c(a = 0, b = 0.6, c = 0.3)
bp <- rnorm(PARTICIPANTS, 0, 0.5); bi <- rnorm(ITEMS, 0, 0.8)
participant <- rep(seq_len(PARTICIPANTS), each = EACH)
item <- as.vector(sapply(seq_len(PARTICIPANTS), function(p) sample(ITEMS, EACH)))
condition <- ifelse(runif(length(item)) < 0.5, "on", "off")
x <- as.numeric(condition == "on")
u <- bp[participant] + bi[item]
rating <- 1 + findInterval(0.4 * x + u + rlogis(length(x)), THRESHOLDS)
numeric <- round(3 + 0.3 * x + u + rnorm(length(x)), 6)
names <- function(prefix, k) sprintf("%s%03d", prefix, k)
ratings <- data.frame(participant = names("P", participant), item = names("I", item),
                      condition = condition, rating = rating, numeric = numeric)
choice_item <- sample(ITEMS, length(participant), replace = TRUE)
pair <- sample(3, length(participant), replace = TRUE)
clip1 <- c("a", "a", "b")[pair]; clip2 <- c("b", "c", "c")[pair]
swap <- runif(length(pair)) < 0.5
tmp <- clip1; clip1 <- ifelse(swap, clip2, clip1); clip2 <- ifelse(swap, tmp, clip2)
eta <- 0.2 + STRENGTH[clip1] - STRENGTH[clip2] + bp[participant] + bi[choice_item]
pairs <- data.frame(participant = names("P", participant), item = names("I", choice_item),
                    clip1 = clip1, clip2 = clip2,
                    x_b = (clip1 == "b") - (clip2 == "b"), x_c = (clip1 == "c") - (clip2 == "c"),
                    first = rbinom(length(eta), 1, plogis(eta)))
write.csv(ratings, gzfile(file.path(folder, "sparse_ratings.csv.gz")), row.names = FALSE)
write.csv(pairs, gzfile(file.path(folder, "sparse_pairs.csv.gz")), row.names = FALSE)

ratings$condition <- factor(ratings$condition, levels = c("off", "on"))
sds <- function(model) {
  frame <- as.data.frame(VarCorr(model))
  setNames(as.list(frame$sdcor), frame$grp)
}
fixed <- function(model) list(fixed = as.list(fixef(model)),
                              se = as.list(sqrt(diag(as.matrix(vcov(model))))),
                              sd = sds(model), loglik = as.numeric(logLik(model)))

reml <- lmerTest::lmer(numeric ~ condition + (1 | participant) + (1 | item), data = ratings)
ml <- update(reml, REML = FALSE)
null <- update(ml, . ~ 1 + (1 | participant) + (1 | item))
table <- summary(reml)$coefficients
profile_ci <- confint(reml, parm = "theta_", method = "profile", oldNames = FALSE)
linear <- c(fixed(reml), list(
  df = table["conditionon", "df"], pvalue = table["conditionon", "Pr(>|t|)"],
  ci = setNames(lapply(seq_len(nrow(profile_ci)), function(i) unname(profile_ci[i, ])),
                rownames(profile_ci)),
  lr = anova(null, ml)$Chisq[2], loglik_ml = as.numeric(logLik(ml))))

ratings$rating_f <- factor(ratings$rating, ordered = TRUE)
m <- clmm(rating_f ~ condition + (1 | participant) + (1 | item), data = ratings)
st <- VarCorr(m)
ordinal <- list(fixed = as.list(coef(m)), se = as.list(summary(m)$coefficients[, "Std. Error"]),
                sd = list(participant = attr(st$participant, "stddev")[[1]],
                          item = attr(st$item, "stddev")[[1]]),
                loglik = as.numeric(logLik(m)))

g <- glmer(first ~ 1 + x_b + x_c + (1 | participant) + (1 | item), data = pairs,
           family = binomial, control = glmerControl(tolPwrss = 1e-12))

out <- list(
  software = list(R = R.version.string, lme4 = as.character(packageVersion("lme4")),
                  lmerTest = as.character(packageVersion("lmerTest")),
                  ordinal = as.character(packageVersion("ordinal"))),
  linear = linear, ordinal = ordinal, pairwise = fixed(g))
write(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE),
      file.path(folder, "sparse_crossed.json"))
