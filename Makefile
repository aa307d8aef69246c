# kinbook: two commands for a fresh machine that has python3 and make.
#   make lab   - create .venv, install kinbook with its extras, register the 'kinbook' kernel, open JupyterLab
#   make test  - create .venv if missing, install, run the unit tests, doctests and nbval on every notebook

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.kinbook-installed
PIN    := requirements/constraints.txt

.PHONY: lab test install kernel lock clean notebooks

install: $(STAMP)

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(STAMP): pyproject.toml $(PIN) | $(BIN)/python
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -c $(PIN) -e '.[lab,test]'
	$(BIN)/python -m ipykernel install --sys-prefix --name kinbook --display-name "Python (kinbook)" >/dev/null
	touch $@

kernel: $(STAMP)

# root (a container, a CI box) needs --allow-root; everyone else gets the plain command
lab: $(STAMP)
	mkdir -p chapters
	$(BIN)/jupyter lab --notebook-dir=chapters $(if $(filter 0,$(shell id -u)),--allow-root)

# -n auto: one pytest worker per core (pytest-xdist); --dist loadfile keeps each notebook's cells in order on
# one worker (they share its kernel). JOBS=1 runs everything in this one process. -rs lists skipped tests with
# their reason (the grading sandbox's tests are skipped where bubblewrap cannot run).
JOBS ?= auto
test: $(STAMP)
	$(BIN)/python -m pytest --nbval --nbval-current-env --nbval-cell-timeout=120 -rs \
		$(if $(filter 1,$(JOBS)),,-n $(JOBS) --dist loadfile)

# Re-execute stored notebooks in place after a library change (NB=path to do only some)
NB ?= chapters/*.ipynb exercises/*.ipynb
notebooks: $(STAMP)
	$(BIN)/jupyter nbconvert --to notebook --execute --inplace --ExecutePreprocessor.kernel_name=kinbook \
		--ExecutePreprocessor.record_timing=False --ExecutePreprocessor.timeout=300 $(wildcard $(NB))

# Re-pin the environment after a dependency change (run on the reference machine class: Python 3.11, Linux).
lock:
	rm -rf .lock-venv && $(PYTHON) -m venv .lock-venv
	.lock-venv/bin/python -m pip install --quiet -e '.[lab,test]'
	{ head -n 3 $(PIN); .lock-venv/bin/python -m pip freeze --exclude-editable | grep -iv '^kinbook'; } > $(PIN).new
	mv $(PIN).new $(PIN) && rm -rf .lock-venv

clean:
	rm -rf $(VENV) build *.egg-info
