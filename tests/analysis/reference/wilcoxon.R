# R's paired Wilcoxon signed-rank tests on the within-subject reference data sets and on
# datasets::sleep, written to wilcoxon_r.json for tests/analysis/test_wilcoxon_r.py.
#
#   Rscript tests/analysis/reference/wilcoxon.R   (from the repository's root)
#
# R's defaults: V = the positive differences' rank sum; exact p for n < 50 without ties
# or zeros, else the normal approximation with continuity correction. Not a dependency:
# run once with Debian's r-base-core and r-cran-jsonlite; the output is committed.
library(jsonlite)
reference <- fromJSON("tests/analysis/reference/within_subject.json", simplifyVector = TRUE)
test <- function(a, b) {
  result <- suppressWarnings(wilcox.test(a, b, paired = TRUE))
  list(V = unname(result$statistic), p = result$p.value, method = result$method)
}
sets <- list()
for (k in seq_len(nrow(reference$datasets))) {
  scores <- reference$datasets$scores[k, ]
  conditions <- sort(names(scores))
  pairs <- list()
  for (i in seq_along(conditions)) for (j in seq_along(conditions)) if (i < j) {
    a <- unlist(scores[[conditions[i]]]); b <- unlist(scores[[conditions[j]]])
    pairs[[length(pairs) + 1]] <- c(list(a = conditions[i], b = conditions[j]), test(a, b))
  }
  sets[[k]] <- pairs
}
sleep <- datasets::sleep
sleep_test <- test(sleep$extra[sleep$group == 2], sleep$extra[sleep$group == 1])
out <- list(software = R.version.string, within_subject = sets,
            sleep = c(list(a = "group 2", b = "group 1",
                           a_values = sleep$extra[sleep$group == 2],
                           b_values = sleep$extra[sleep$group == 1]), sleep_test))
writeLines(toJSON(out, auto_unbox = TRUE, digits = NA, pretty = TRUE),
           "tests/analysis/reference/wilcoxon_r.json")
