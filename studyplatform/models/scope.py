"""Say where each model's study is: the lookup from a row to the study it belongs to."""

# The lookup from each model (by model name) to its study; "" for the study itself.
# The admin scopes lists and choices by it, and actions check ownership with it.
STUDY_PATHS: dict[str, str] = {
    "study": "",
    "condition": "study",
    "item": "study",
    "question": "study",
    "answeroption": "question__study",
    "block": "study",
    "trial": "study",
    "stimulus": "condition__study",
    "recording": "item__study",
    "uploadedclip": "condition__study",
    "participant": "study",
    "personalanswer": "participant__study",
    "response": "participant__study",
    "mediaevent": "participant__study",
}
