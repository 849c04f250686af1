"""Every gearloss example in README.md and docs/ is marked and the quick ones run as documented:
``workflows/doc_examples.py`` extracts the fenced blocks; ``python -m workflows.doc_examples --all`` runs the slow
ones (the main job) too."""

import pytest

from workflows.doc_examples import extract, pages, run_pages


def test_every_block_with_a_gearloss_command_is_marked():
    unmarked = [(path.name, line, command) for path in pages() for line, command in extract(path)[1]]
    assert not unmarked, unmarked
    examples = [e for path in pages() for e in extract(path)[0] if e.kind == "example"]
    assert len(examples) >= 10 and any(e.slow for e in examples)
    readme = [e for e in extract(pages()[0])[0] if e.kind == "example"]
    assert {c[0] for e in readme for c in e.commands} >= {"pipeline", "contact", "surrogate", "gear"}


@pytest.mark.slow
def test_the_quick_examples_run_as_documented():
    failures = run_pages(include_slow=False, verbose=False)
    assert not failures, "\n".join(failures)
