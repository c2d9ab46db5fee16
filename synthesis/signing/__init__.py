"""Signed sentences: the sign library, seed 003's automated spine, liveliness, synthesis."""

from synthesis.signing.sentence import Sentence, SentenceOptions, synthesize
from synthesis.signing.signs import SignError, SignLibrary, read_library

__all__ = ["Sentence", "SentenceOptions", "SignError", "SignLibrary", "read_library", "synthesize"]
