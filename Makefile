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

.PHONY: help install install-dev lock lab fresh test portable notebooks bench bench-quick bench-widgets bench-peers bench-first-lab student grade site dist browser-test clean

help:
	@echo "make lab        open the course in JupyterLab, on the start page notebooks/$(START_PAGE);"
	@echo "                the first time, creates .venv and installs the course (requirements.txt, with $(INSTALLER));"
	@echo "                extra JupyterLab options: make lab LAB_ARGS=\"--no-browser --port 8890\""
	@echo "                it opens your copies of the chapters in work/ (git ignores them: git pull always works)"
	@echo "make fresh NOTEBOOK=03_jacobian_velocity.ipynb  the course's version of a chapter in work/ again (yours kept as .ipynb~)"
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
	@echo "make grade SUBMISSIONS=folder [OUT=file.csv] [JOBS=n] [UNSAFE=1]  grade returned notebooks, each in a sandbox, n at a time;"
	@echo "                verdicts from the answers, hidden inputs and calls; grades, gradebook (nbgrader columns), points and"
	@echo "                feedback per student beside the CSV (UNSAFE=1: no sandbox, trusted notebooks only)"
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
	@$(CHECK_PYTHON)
	@echo "make: installing the course (requirements.txt) into $(VENV) with $(INSTALLER)$(if $(UV),, (uv is not on the PATH; with it the install is faster))"
	@test -x $(BIN)/python || { $(PYTHON) -m venv $(VENV) && touch $(NEW_VENV) $(if $(UV),,&& $(BIN)/python -m pip install --quiet --upgrade pip); } || { $(UNDO_NEW_VENV); exit 1; }
	$(QUIET_SETUPTOOLS) $(INSTALL) -r requirements.txt -c constraints.txt || { $(UNDO_NEW_VENV); exit 1; }
	$(COMPILE)
	@rm -f $(NEW_VENV)
	rm -rf $(LABEXTENSION_LINK)
	mkdir -p $(dir $(LABEXTENSION_LINK))
	ln -s "$(CURDIR)/labextension/twolink_figure_alt/labextension" $(LABEXTENSION_LINK)
	@touch $@

$(STAMP): $(COURSE_STAMP) requirements-dev.txt
	@echo "make: installing the developers' tools (requirements-dev.txt) into $(VENV) with $(INSTALLER)"
	$(QUIET_SETUPTOOLS) $(INSTALL) -r requirements-dev.txt -c constraints.txt
	$(COMPILE)
	@touch $@

# Python first, before minutes of install: the course needs 3.11 or newer (numpy 2.4
# and the pinned packages), and a .venv made by an older Python is reported, not reused.
MIN_PYTHON := 3.11
PYTHON_IS_NEW_ENOUGH = -c 'import sys; sys.exit(sys.version_info < ($(subst .,$(comma),$(MIN_PYTHON)),))'
comma := ,
CHECK_PYTHON = \
	if test -x $(BIN)/python; then \
		$(BIN)/python $(PYTHON_IS_NEW_ENOUGH) 2>/dev/null || { echo "make: $(VENV) was made with $$($(BIN)/python --version 2>&1), older than Python $(MIN_PYTHON); remove it and start again with a newer Python: rm -rf $(VENV) && make lab PYTHON=python$(MIN_PYTHON)"; exit 1; }; \
	else \
		command -v $(PYTHON) >/dev/null 2>&1 || { echo "make: $(PYTHON) was not found; the course needs Python $(MIN_PYTHON) or newer (https://www.python.org/downloads/), then: make lab PYTHON=python$(MIN_PYTHON)"; exit 1; }; \
		$(PYTHON) $(PYTHON_IS_NEW_ENOUGH) 2>/dev/null || { echo "make: the course needs Python $(MIN_PYTHON) or newer, and $(PYTHON) is $$($(PYTHON) --version 2>&1); install Python $(MIN_PYTHON)+ (https://www.python.org/downloads/, or your system's python$(MIN_PYTHON) package), then: make lab PYTHON=python$(MIN_PYTHON)"; exit 1; }; \
	fi
# A .venv this make created and whose install failed is removed, so the next make starts
# afresh (an existing .venv whose update failed is kept: it worked before).
NEW_VENV = $(VENV)/.new-venv
UNDO_NEW_VENV = if test -f $(NEW_VENV); then rm -rf $(VENV); echo "make: the install failed, so the new $(VENV) was removed (the next make starts afresh); the messages above say why"; fi
# setuptools' editable install prints a warning box about folders named like the
# package: true of every clone, and nothing a learner can act on.
QUIET_SETUPTOOLS = PYTHONWARNINGS="ignore:Editable installation$${PYTHONWARNINGS:+,$$PYTHONWARNINGS}"

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
# tools/lab_server/settings/: the course's JupyterLab defaults (no news prompt over the
# explorers, no update check; nbgrader's menus and panels, which make site, make student
# and make test install for teachers, are hidden from the learner's JupyterLab), and
# nbgrader's server extensions are not started (their start-up warnings stay out too).
NBGRADER_SERVER_EXTENSIONS := formgrader validate_assignment assignment_list course_list
LAB_SERVER := PYTHONPATH="$(CURDIR)/tools/lab_server$${PYTHONPATH:+:$$PYTHONPATH}" \
	$(BIN)/jupyter lab --ServerApp.jpserver_extensions=twolink_nodelay=True \
	$(foreach name,$(NBGRADER_SERVER_EXTENSIONS),--ServerApp.jpserver_extensions=nbgrader.server_extensions.$(name)=False) \
	--LabApp.app_settings_dir="$(CURDIR)/tools/lab_server/settings"

# The learner's copies of the chapters: make lab opens work/ (git ignores it), where each
# chapter is copied from notebooks/ the first time; running and saving a chapter never
# changes the course's files, so git pull always works.  A chapter of the course's newer
# version (after git pull), or the course's version again: delete its copy in work/ and
# run make lab (make fresh NOTEBOOK=03_jacobian_velocity.ipynb keeps yours as .ipynb~).
WORK ?= work
COPY_CHAPTERS = mkdir -p $(WORK) && for notebook in notebooks/*.ipynb; do \
	test -e "$(WORK)/$${notebook\#\#*/}" || cp "$$notebook" "$(WORK)/"; done

# JupyterLab opens on the start page (its default URL) instead of the Launcher.
lab: $(COURSE_STAMP)
	@$(if $(ALLOW_ROOT),echo "$(ROOT_NOTE)",:)
	@$(COPY_CHAPTERS)
	$(LAB_SERVER) --ServerApp.root_dir=$(WORK) --LabApp.default_url=/lab/tree/$(START_PAGE) $(ALLOW_ROOT) $(LAB_ARGS)

NOTEBOOK ?=
fresh:
	@test -n "$(NOTEBOOK)" -a -f "notebooks/$(NOTEBOOK)" || { echo "usage: make fresh NOTEBOOK=03_jacobian_velocity.ipynb (a file of notebooks/)"; exit 2; }
	@mkdir -p $(WORK)
	@if test -e "$(WORK)/$(NOTEBOOK)"; then mv "$(WORK)/$(NOTEBOOK)" "$(WORK)/$(NOTEBOOK)~"; echo "make: your copy is now $(WORK)/$(NOTEBOOK)~"; fi
	cp "notebooks/$(NOTEBOOK)" "$(WORK)/$(NOTEBOOK)"

# Options for pytest (doctests, strict nbval, sanitize file, xdist) live in
# pyproject.toml so that a plain `pytest` in the venv behaves the same.
# First the static checks, once each and in seconds, leaving no cache in the checkout:
# the layers (import-linter's contracts in pyproject.toml: the library never imports
# the course kit, no import cycle in either), ruff's lint and format, mypy (with a
# worker per core, which needs a cache: a temporary folder, removed after; 6 s instead
# of 10 on 2 cores).  Then pytest: every folder of tests/ but tests/benchmarks, the
# doctests, each chapter once under strict nbval with its figure and exercise checks.
test: $(STAMP)
	$(BIN)/lint-imports --no-cache
	$(BIN)/ruff check --no-cache --quiet .
	$(BIN)/ruff format --check --no-cache --quiet .
	@cache=$$(mktemp -d) && echo "$(BIN)/mypy --num-workers=auto --cache-dir=$$cache" && \
	$(BIN)/mypy --num-workers=auto --cache-dir="$$cache"; typed=$$?; rm -rf "$$cache"; exit $$typed
	$(BIN)/python -m pytest

# Stored outputs must read the same on every CPU, BLAS kernel and OS: strict
# nbval of the chapters once per emulated numeric environment (tools/portable.py
# lists them).  One chapter: make portable NOTEBOOKS=notebooks/04_statics_wall.ipynb;
# some variants: make portable VARIANTS="avx2-haswell sse-1-thread"; all but some:
# make portable EXCEPT=as-installed (what .ci/run does: its make test has just run that one).
portable: $(STAMP)
	$(BIN)/python tools/portable.py $(addprefix --variant ,$(VARIANTS)) $(addprefix --except ,$(EXCEPT)) $(if $(filter command line,$(origin NOTEBOOKS)),$(NOTEBOOKS),)

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

# The teacher's two targets need the course's install only (make install: requirements.txt
# brings nbformat, nbclient and jupyter_client with JupyterLab); tests/infrastructure/test_grade.py checks it.
student: $(COURSE_STAMP)
	$(BIN)/python tools/editions.py student --out build/student

SUBMISSIONS ?=
OUT ?=
grade: $(COURSE_STAMP)
	@test -n "$(SUBMISSIONS)" || { echo "usage: make grade SUBMISSIONS=folder-of-returned-notebooks [OUT=grades.csv] [JOBS=n] [UNSAFE=1]"; exit 2; }
	$(BIN)/python tools/grade.py "$(SUBMISSIONS)" $(if $(OUT),--out "$(OUT)",) $(if $(JOBS),--jobs $(JOBS),) $(if $(UNSAFE),--unsafe,)

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
