# twolink: the two commands a learner needs are `make lab` and `make test`.
# Both create the virtual environment .venv on first use.

PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed-stamp
NOTEBOOKS := $(sort $(wildcard notebooks/*.ipynb))

.PHONY: help install lab test notebooks bench student site browser-test clean

help:
	@echo "make lab        open the course in JupyterLab (creates .venv on first use)"
	@echo "make test       unit tests, doctests, notebook hygiene and every notebook under strict nbval"
	@echo "make notebooks  re-execute and normalise every notebook (after editing one)"
	@echo "make bench      print the speed benchmark tables"
	@echo "make student    write the student edition (solutions stubbed) to build/student/"
	@echo "make site       render the executed chapters to static HTML in build/site/"
	@echo "make browser-test  run only the browser suite (JupyterLab and the site in Chromium)"

$(STAMP): requirements.txt pyproject.toml
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r requirements.txt
	@touch $(STAMP)

install: $(STAMP)

# JupyterLab refuses to run as root unless told; containers and CI machines often are root.
ALLOW_ROOT := $(if $(filter 0,$(shell id -u 2>/dev/null)),--allow-root,)

lab: $(STAMP)
	$(BIN)/jupyter lab --ServerApp.root_dir=notebooks $(ALLOW_ROOT)

# Options for pytest (doctests, strict nbval, sanitize file, xdist) live in
# pyproject.toml so that a plain `pytest` in the venv behaves the same.
test: $(STAMP)
	$(BIN)/python -m pytest

# Widget state is stored while executing (nbclient 0.11 raises KeyError on an
# interactive() output otherwise) and then removed by nbstripout, with the
# other metadata GitHub and nbval do not need.
notebooks: $(STAMP)
	@for notebook in $(NOTEBOOKS); do \
		echo "executing $$notebook"; \
		env -u MPLBACKEND $(BIN)/jupyter nbconvert --to notebook --execute --inplace \
			--ExecutePreprocessor.timeout=600 \
			--ExecutePreprocessor.record_timing=False \
			"$$notebook" || exit 1; \
		$(BIN)/nbstripout --keep-output --keep-count "$$notebook" || exit 1; \
	done

bench: $(STAMP)
	@for script in benchmarks/bench_*.py; do $(BIN)/python "$$script" || exit 1; done

student: $(STAMP)
	$(BIN)/python tools/editions.py student --out build/student

site: $(STAMP)
	$(BIN)/python tools/editions.py site --out build/site

browser-test: $(STAMP)
	$(BIN)/python -m pytest -m browser tests/browser -n 0 -s

clean:
	rm -rf build .pytest_cache
