"""The regression corpus of issue 10, run in one capped worker process."""

from __future__ import annotations

from .corpus import CORPUS
from .harness import check_all


def test_corpus_ids_are_unique():
    ids = [c["id"] for c in CORPUS]
    assert len(ids) == len(set(ids))


def test_every_corpus_case_is_refused_cleanly_or_succeeds():
    check_all(CORPUS)
