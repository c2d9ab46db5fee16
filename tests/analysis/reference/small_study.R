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

source(file.path(here, "paired_tests.R"))  # signed_rank, dz_ci, paired
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
