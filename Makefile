# twolink: the two commands a learner needs are `make lab` and `make test`.
# Both create the virtual environment .venv on first use: `make lab` installs
# what the course needs (requirements.txt), `make test` and the other
# developers' targets add the developers' tools (requirements-dev.txt).

PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin
# Two install stamps: the course's (make lab) and the developers' (make test,
# ...), which includes the course's.
COURSE_STAMP := $(VENV)/.course-stamp
STAMP := $(VENV)/.installed-stamp
NOTEBOOKS := $(sort $(wildcard notebooks/*.ipynb))
# The notebook JupyterLab opens first (make lab).
START_PAGE ?= 00_start_here.ipynb

# The installer: uv when it is on the PATH (several times faster), pip otherwise.
# Both compile the packages' bytecode in parallel after installing (pip itself
# compiles file by file, 26 of its 38 s here), so that the first imports are quick.
UV := $(shell command -v uv 2>/dev/null)
ifneq ($(UV),)
INSTALLER := uv
INSTALL := $(UV) pip install --quiet --compile-bytecode --python $(BIN)/python
COMPILE :=
else
INSTALLER := pip
INSTALL := $(BIN)/python -m pip install --quiet --no-compile
COMPILE := $(BIN)/python -m compileall -q -j 0 "$$($(BIN)/python -c 'import sysconfig; print(sysconfig.get_path("purelib"))')" >/dev/null || echo "make: some files did not compile (Python compiles them when imported)"
endif

.PHONY: help install install-dev lock lab test portable notebooks bench bench-quick bench-widgets bench-peers bench-first-lab student grade site dist browser-test clean

help:
	@echo "make lab        open the course in JupyterLab, on the start page notebooks/$(START_PAGE);"
	@echo "                the first time, creates .venv and installs the course (requirements.txt, with $(INSTALLER));"
	@echo "                extra JupyterLab options: make lab LAB_ARGS=\"--no-browser --port 8890\""
	@echo "make install    install (or, after git pull, update) what make lab needs, without starting JupyterLab"
	@echo "make install-dev  that and the developers' tools (requirements-dev.txt); every target below does it first"
	@echo "make test       import layers, ruff, mypy, then pytest: unit tests, doctests, every chapter once under strict"
	@echo "                nbval (with its figure and exercise checks), the infrastructure tests (venvs, wheels, grading,"
	@echo "                editions, browser); while working: .venv/bin/python -m pytest tests/library (or tests/course, ...);"
	@echo "                all but the infrastructure: .venv/bin/python -m pytest -m \"not infrastructure\""
	@echo "make portable   every chapter (strict nbval) and doctest in several emulated numeric environments (CPU SIMD, BLAS kernels, threads)"
	@echo "make notebooks  re-execute and normalise every notebook (after editing one)"
	@echo "make bench      print the speed benchmark tables (bench-widgets included)"
	@echo "make bench-quick  every benchmark at its --quick sizes, checked to print its table (CI's step after make test)"
	@echo "make bench-widgets  key press to a changed picture for every explorer, in JupyterLab in Chromium"
	@echo "make bench-first-lab  a fresh clone's first make lab until the start page is served (pip, and uv if on the PATH)"
	@echo "make bench-peers  twolink beside roboticstoolbox (ik_LM) and pinocchio (aba, rnea), in build/peers-venv"
	@echo "make student    write the student edition (solutions stubbed, the start page, a twolink wheel) to build/student/ and build/student.zip"
	@echo "make grade SUBMISSIONS=folder [JOBS=n] [UNSAFE=1]  grade returned notebooks, each in a sandbox, n at a time;"
	@echo "                verdicts from the answers; CSV + one line per notebook (UNSAFE=1: no sandbox, trusted notebooks only)"
	@echo "make site       render the executed chapters to static HTML in build/site/"
	@echo "make dist       build the sdist and the wheel into dist/ and check them with twine (DIST=folder elsewhere)"
	@echo "make browser-test  run only the browser suite (JupyterLab and the site in Chromium)"
	@echo "make lock       regenerate constraints.txt (every package's exact version) from a clean venv of both requirement files"
	@echo "Installs use uv when it is on the PATH, pip otherwise."

# requirements.txt names what the course needs, requirements-dev.txt adds the
# developers' tools (tests, notebook hygiene, grading, the static site,
# publishing); constraints.txt pins every package either brings (indirect ones
# too), so the stored notebook outputs are reproduced.  `make lock` regenerates it.
# The venv is Python's own (python -m venv: pip and setuptools as the lock was
# made with) whichever installer fills it; pip upgrades itself first (the new
# one installs the course ~10 s faster).
$(COURSE_STAMP): requirements.txt constraints.txt pyproject.toml
	@echo "make: installing the course (requirements.txt) into $(VENV) with $(INSTALLER)$(if $(UV),, (uv is not on the PATH; with it the install is faster))"
	@test -x $(BIN)/python || { $(PYTHON) -m venv $(VENV) $(if $(UV),,&& $(BIN)/python -m pip install --quiet --upgrade pip); }
	$(INSTALL) -r requirements.txt -c constraints.txt
	$(COMPILE)
	rm -rf $(LABEXTENSION_LINK)
	mkdir -p $(dir $(LABEXTENSION_LINK))
	ln -s "$(CURDIR)/labextension/twolink_figure_alt/labextension" $(LABEXTENSION_LINK)
	@touch $@

$(STAMP): $(COURSE_STAMP) requirements-dev.txt
	@echo "make: installing the developers' tools (requirements-dev.txt) into $(VENV) with $(INSTALLER)"
	$(INSTALL) -r requirements-dev.txt -c constraints.txt
	$(COMPILE)
	@touch $@

# The prebuilt JupyterLab extension twolink-figure-alt (labextension/: figures'
# alt text in JupyterLab).  A wheel installs it from pyproject's data-files, but
# the editable install of requirements.txt (-e .) skips data-files, so it is
# linked into the venv, where JupyterLab looks; the link follows a rebuild
# (python labextension/build.py).
LABEXTENSION_LINK := $(VENV)/share/jupyter/labextensions/twolink-figure-alt

# What `make lab` installs (after a `git pull`, the course's new versions), and with the developers' tools.
install: $(COURSE_STAMP)
install-dev: $(STAMP)

# A throwaway venv with requirements-dev.txt (which includes requirements.txt), frozen:
# what a clean install of both files resolves today.
LOCK_VENV := build/lock-venv
lock:
	rm -rf $(LOCK_VENV)
	$(PYTHON) -m venv $(LOCK_VENV)
	$(LOCK_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(LOCK_VENV)/bin/python -m pip install --quiet -r requirements-dev.txt
	{ echo "# Generated by \`make lock\` from a clean install of requirements-dev.txt, which includes requirements.txt ($$($(LOCK_VENV)/bin/python -c 'import platform; print("Python", platform.python_version())')): do not edit by hand."; \
	  echo "# Used as constraints by every install (make lab, make test, CI, Binder): pip install -r requirements.txt -c constraints.txt"; \
	  $(LOCK_VENV)/bin/python -m pip freeze --all --exclude-editable | grep -v '^pip=='; } > constraints.txt.new
	mv constraints.txt.new constraints.txt
	rm -rf $(LOCK_VENV)

# JupyterLab refuses to run as root unless given --allow-root; containers and CI
# machines often are root, so `make lab` adds it there and says so.
ALLOW_ROOT := $(if $(filter 0,$(shell id -u 2>/dev/null)),--allow-root,)
ROOT_NOTE := make lab: you are root, and JupyterLab refuses to run as root (a notebook could change the whole machine), so --allow-root is added; to avoid it, run make lab as an ordinary user (in a container: docker run --user)

# Extra JupyterLab options: make lab LAB_ARGS="--no-browser --port 8890"
LAB_ARGS ?=

# tools/lab_server/twolink_nodelay.py: kernel messages reach the browser
# without Nagle's delay (explorers answer 15-40 ms sooner).
LAB_SERVER := PYTHONPATH="$(CURDIR)/tools/lab_server$${PYTHONPATH:+:$$PYTHONPATH}" \
	$(BIN)/jupyter lab --ServerApp.jpserver_extensions=twolink_nodelay=True

# JupyterLab opens on the start page (its default URL) instead of the Launcher.
lab: $(COURSE_STAMP)
	@$(if $(ALLOW_ROOT),echo "$(ROOT_NOTE)",:)
	$(LAB_SERVER) --ServerApp.root_dir=notebooks --LabApp.default_url=/lab/tree/$(START_PAGE) $(ALLOW_ROOT) $(LAB_ARGS)

# Options for pytest (doctests, strict nbval, sanitize file, xdist) live in
# pyproject.toml so that a plain `pytest` in the venv behaves the same.
# First the static checks, once each and in seconds, leaving no cache in the checkout:
# the layers (import-linter's contracts in pyproject.toml: the library never imports
# the course kit, no import cycle in either), ruff's lint and format, mypy.  Then
# pytest: every folder of tests/ but tests/benchmarks, the doctests, each chapter once
# under strict nbval with its figure and exercise checks.
test: $(STAMP)
	$(BIN)/lint-imports --no-cache
	$(BIN)/ruff check --no-cache --quiet .
	$(BIN)/ruff format --check --no-cache --quiet .
	$(BIN)/mypy --cache-dir=/dev/null
	$(BIN)/python -m pytest

# Stored outputs must read the same on every CPU, BLAS kernel and OS: strict
# nbval of the chapters once per emulated numeric environment (tools/portable.py
# lists them).  One chapter: make portable NOTEBOOKS=notebooks/04_statics_wall.ipynb
portable: $(STAMP)
	$(BIN)/python tools/portable.py $(if $(filter command line,$(origin NOTEBOOKS)),$(NOTEBOOKS),)

# First the generated cells: the install cell, the start page's map and the chapters' links,
# nbgrader's metadata (tools/install_cell.py, tools/course_map.py, tools/nbgrader_cells.py).
# Widget state is stored while executing (nbclient 0.11 raises KeyError on an
# interactive() output otherwise) and then removed by nbstripout, with the
# other metadata GitHub and nbval do not need.
notebooks: $(STAMP)
	$(BIN)/python tools/install_cell.py
	$(BIN)/python tools/course_map.py
	$(BIN)/python tools/nbgrader_cells.py $(NOTEBOOKS)
	@for notebook in $(NOTEBOOKS); do \
		echo "executing $$notebook"; \
		env -u MPLBACKEND $(BIN)/jupyter nbconvert --to notebook --execute --inplace \
			--ExecutePreprocessor.timeout=600 \
			--ExecutePreprocessor.record_timing=False \
			"$$notebook" || exit 1; \
		$(BIN)/nbstripout --keep-output --keep-count "$$notebook" || exit 1; \
	done

# bench_first_lab.py (a fresh clone's first `make lab`: minutes, and the package index) runs alone.
bench: $(STAMP)
	@for script in $(filter-out benchmarks/bench_first_lab.py,$(sort $(wildcard benchmarks/bench_*.py))); do $(BIN)/python "$$script" || exit 1; done

# Every benchmark script at its --quick sizes, checked to print its table (tests/benchmarks/):
# not part of make test; CI runs it as its own step after make test.
bench-quick: $(STAMP)
	$(BIN)/python -m pytest tests/benchmarks --dist load

bench-first-lab: $(STAMP)
	$(BIN)/python benchmarks/bench_first_lab.py

bench-widgets: $(STAMP)
	$(BIN)/python benchmarks/bench_widgets.py

# Optional: the peers are not course requirements, so they go into their own venv.
# A peer that will not install is reported by benchmarks/peers.py, not fatal.
PEERS_VENV := build/peers-venv
bench-peers:
	@test -x $(PEERS_VENV)/bin/python || $(PYTHON) -m venv $(PEERS_VENV)
	$(PEERS_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(PEERS_VENV)/bin/python -m pip install --quiet .
	-$(PEERS_VENV)/bin/python -m pip install --quiet roboticstoolbox-python
	-$(PEERS_VENV)/bin/python -m pip install --quiet pin
	cd build && ../$(PEERS_VENV)/bin/python ../benchmarks/peers.py

student: $(STAMP)
	$(BIN)/python tools/editions.py student --out build/student

SUBMISSIONS ?=
grade: $(STAMP)
	@test -n "$(SUBMISSIONS)" || { echo "usage: make grade SUBMISSIONS=folder-of-returned-notebooks"; exit 2; }
	$(BIN)/python tools/grade.py "$(SUBMISSIONS)" $(if $(JOBS),--jobs $(JOBS),) $(if $(UNSAFE),--unsafe,)

site: $(STAMP)
	$(BIN)/python tools/editions.py site --out build/site

# The sdist and the wheel, ready to upload: `python -m build` makes the sdist, then
# the wheel from it (so a file missing from the sdist is missing from the wheel
# too), each in an isolated environment with the build backend pyproject.toml
# names; `twine check --strict` reads their metadata and README as PyPI would.
# tests/infrastructure/test_dist.py checks what they hold.
DIST ?= dist
dist: $(STAMP)
	rm -f $(DIST)/twolink-*.tar.gz $(DIST)/twolink-*.whl
	$(BIN)/python -m build --outdir $(DIST) .
	$(BIN)/python -m twine check --strict $(DIST)/twolink-*

browser-test: $(STAMP)
	$(BIN)/python -m pytest -m browser tests/browser -n 0 -s

clean:
	rm -rf build dist .pytest_cache
