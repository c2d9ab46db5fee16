# Recompute the golden report test's statistics in R from small_study.csv
# (tests/analysis/test_golden_report.py). Base R and jsonlite only (Debian's r-base-core,
# r-cran-jsonlite); run from the repository root:
#     Rscript tests/analysis/reference/small_study.R
# Writes tests/analysis/reference/small_study.json.
library(jsonlite)
here <- "tests/analysis/reference"
d <- read.csv(file.path(here, "small_study.csv"), colClasses = "character")
d <- d[d$flags != "practice", ]
names_of <- function(key) {
  labels <- unique(rbind(setNames(d[, c("condition_a", "condition_a_label")], c("k", "l")),
                         setNames(d[, c("condition_b", "condition_b_label")], c("k", "l"))))
  labels$l[match(key, labels$k)]
}
conditions <- sort(names_of(unique(d$condition_a[d$kind == "pairwise"])))
pairs <- combn(conditions, 2, simplify = FALSE)

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
holm <- function(results, field) p.adjust(sapply(results, function(r) r[[field]]), "holm")

# Pairwise: binomial tests per pair (ties excluded), per-participant win rates.
pw <- d[d$kind == "pairwise", ]
pw$a <- names_of(pw$condition_a); pw$b <- names_of(pw$condition_b)
pw$chosen_name <- ifelse(pw$chosen == "none", "none", names_of(pw$chosen))
binomial <- lapply(pairs, function(p) {
  rows <- pw[(pw$a == p[1] & pw$b == p[2]) | (pw$a == p[2] & pw$b == p[1]), ]
  wins <- sum(rows$chosen_name == p[1]); losses <- sum(rows$chosen_name == p[2])
  b <- binom.test(wins, wins + losses)
  list(a = p[1], b = p[2], a_wins = wins, b_wins = losses, ties = sum(rows$chosen_name == "none"),
       p = b$p.value)
})
adjusted <- holm(binomial, "p")
for (i in seq_along(binomial)) binomial[[i]]$p_adjusted <- adjusted[i]

participants <- sort(unique(pw$participant))
rate <- sapply(conditions, function(c) sapply(participants, function(who) {
  mine <- pw[pw$participant == who, ]
  sum(mine$chosen_name == c) / sum(mine$a == c | mine$b == c)
}))
by_pair <- function(scores, test) {
  lapply(pairs, function(p) c(list(a = p[1], b = p[2]), test(scores[, p[1]], scores[, p[2]])))
}
adjust_all <- function(results, field, into) {
  adjusted <- holm(results, field)
  for (i in seq_along(results)) results[[i]][[into]] <- adjusted[i]
  results
}
posthoc <- adjust_all(by_pair(rate, paired), "p", "p_adjusted")
wilcoxon <- adjust_all(by_pair(rate, signed_rank), "p", "p_adjusted")

# Across items: each participant's mean per condition, then paired tests and summaries.
across <- function(rows, score) {
  rows$name <- names_of(rows$condition_a)
  rows$score <- score
  means <- sapply(conditions, function(c) sapply(participants, function(who)
    mean(rows$score[rows$participant == who & rows$name == c])))
  summary <- lapply(conditions, function(c) {
    m <- means[, c]; s <- rows$score[rows$name == c]
    t <- t.test(m)
    list(condition = c, n = length(s), participants = length(m), mean = mean(m), sd = sd(m),
         sem = sd(m) / sqrt(length(m)), ci = as.numeric(t$conf.int), median = median(s),
         q1 = unname(quantile(s, 0.25, type = 7)), q3 = unname(quantile(s, 0.75, type = 7)))
  })
  tests <- adjust_all(by_pair(means, paired), "p", "t_p_adjusted")
  ranks <- adjust_all(by_pair(means, signed_rank), "p", "wilcoxon_p_adjusted")
  list(conditions = summary, comparisons = mapply(function(t, w) c(t, list(
    wilcoxon_V = w$V, wilcoxon_p = w$p, wilcoxon_p_adjusted = w$wilcoxon_p_adjusted,
    rank_biserial = w$r)), tests, ranks, SIMPLIFY = FALSE))
}
ratings <- d[d$kind == "rating", ]
texts <- d[d$kind == "text", ]
# Whole-word accuracy: the share of the target's words found in the answer, each used once.
accuracy <- mapply(function(answer, target) {
  given <- strsplit(toupper(answer), "[^A-Z0-9']+")[[1]]
  wanted <- strsplit(toupper(target), "[^A-Z0-9']+")[[1]]
  found <- 0
  for (w in wanted) if (w %in% given) { given <- given[-match(w, given)]; found <- found + 1 }
  found / length(wanted)
}, texts$text, texts$target)

out <- list(
  source = paste("R", getRversion(), "— tests/analysis/reference/small_study.R"),
  pairs = binomial, posthoc = posthoc, wilcoxon = wilcoxon,
  ratings = across(ratings, as.numeric(ratings$rating)),
  intelligibility = across(texts, unname(accuracy))
)
write_json(out, file.path(here, "small_study.json"), auto_unbox = TRUE, digits = NA, pretty = TRUE)
cat("wrote", file.path(here, "small_study.json"), "\n")
