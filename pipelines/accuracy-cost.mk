# accuracy-cost: what accuracy costs in time (issue 7 §1), for the polygon DEM.
# Knobs: the time step (safety factor 2^-1 … 2^-7 of each integrator's stability bound), the integrator
# (gear5, verlet) and the resolution (cells per sample over two decades).
# Errors: energy drift of the undamped elastic pulse and the rms displacement at t = 2e-4 s against a
# reference run (gear5 at 2^-9 of its bound); for resolution, the effective Young modulus K against the
# finest mesh. Cost: wall time, steps, cell-steps per second, peak memory (GNU time).
#   make -f Makefile.analysis accuracy-cost
AC := $(RESULTS)/accuracy-cost
AC_LEVELS := 1 2 3 4 5 6 7
AC_INTEGRATORS := gear5 verlet
AC_PULSE := --stop.t_max 2e-4 --output.frame_interval 1 --output.observe_every 5 --loading.energy 5
# Resolutions: nx x ny cells of a 0.25 m × 0.40 m sample (g from 2.5 cm to 0.25 cm).
AC_RESOLUTIONS := 10x16 18x29 25x40 40x64 56x90 100x160

.PHONY: accuracy-cost
accuracy-cost: $(AC)/table.md $(AC)/error-vs-time.png $(AC)/resolution.png
	@cat $(AC)/table.md

$(AC)/disc.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.2 --cells 300 --seed 1 -q -o $@

# dt/<integrator>-<level>.h5: dt = 2^-level × the integrator's bound; its cost in .time (wall s, peak kB).
.SECONDEXPANSION:
$(AC)/dt/%.h5: $(AC)/disc.h5 data/scenes/pulse.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r kind level <<< "$*"; echo "dem-run pulse $$kind at 2^-$$level of the bound"; \
	$(RUN_ENV) /usr/bin/time -f "%e %M" -o $(AC)/dt/$*.time $(BIN)/dem-run --scene data/scenes/pulse.ini $< -q -o $@ \
	  $(AC_PULSE) --integrator.kind $$kind --integrator.dt auto \
	  --integrator.safety $$(awk -v l=$$level 'BEGIN { print 2 ^ -l }')

$(AC)/reference.h5: $(AC)/disc.h5 data/scenes/pulse.ini | build
	$(RUN_ENV) $(BIN)/dem-run --scene data/scenes/pulse.ini $< -q -o $@ $(AC_PULSE) --integrator.kind gear5 \
	  --integrator.dt auto --integrator.safety $$(awk 'BEGIN { print 2 ^ -9 }')

# One row per run: integrator,level,dt,steps,wall_s,peak_MB,cell_steps_per_s,energy_drift,rms_displacement_error
$(AC)/dt/%.row: $(AC)/dt/%.h5 $(AC)/reference.h5
	@IFS=- read -r kind level <<< "$*"; read -r wall mem < $(AC)/dt/$*.time; \
	dt=$$($(BIN)/observables $< --parameter derived.dt); \
	steps=$$(h5dump -a /steps $< | awk '/\(0\)/ { print $$2 }'); \
	drift=$$($(BIN)/observables $< --columns energy_balance | awk -F, 'NR == 2 { e0 = $$2 } NR > 1 { d = $$2 - e0; if (d < 0) d = -d; if (d > m) m = d } END { printf "%.4g", m / e0 }'); \
	err=$$($(BIN)/observables $< --compare $(AC)/reference.h5 | awk '$$1 == "rms_position_difference" { print $$2 }'); \
	awk -v k=$$kind -v l=$$level -v dt=$$dt -v s=$$steps -v w=$$wall -v m=$$mem -v d=$$drift -v e=$$err \
	  'BEGIN { printf "%s,%s,%s,%s,%s,%.1f,%.4g,%s,%s\n", k, l, dt, s, w, m / 1024, 300 * s / (w > 0 ? w : 1e-3), d, e }' > $@

$(AC)/timestep.csv: $(foreach k,$(AC_INTEGRATORS),$(foreach l,$(AC_LEVELS),$(AC)/dt/$(k)-$(l).row))
	@{ echo "integrator,level,dt_s,steps,wall_s,peak_MB,cell_steps_per_s,energy_drift,rms_displacement_error_m"; cat $^; } > $@

# Observed order of convergence of each integrator: slope of log(error) against log(dt) over the three
# finest levels above the reference's resolution.
$(AC)/orders.csv: $(AC)/timestep.csv
	@awk -F, 'NR > 1 && $$2 >= 3 && $$2 <= 6 && $$9 > 0 { x = log($$3); y = log($$9); n[$$1]++; sx[$$1] += x; sy[$$1] += y; sxx[$$1] += x * x; sxy[$$1] += x * y } \
	  END { print "integrator,observed_order_displacement"; for (k in n) printf "%s,%.2f\n", k, (n[k] * sxy[k] - sx[k] * sy[k]) / (n[k] * sxx[k] - sx[k] * sx[k]) }' $< > $@

$(AC)/mesh-%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape rect --size 0.25x0.40 --cells $* --seed 1 -q -o $@

$(AC)/res/%.h5: $(AC)/mesh-%.h5 data/scenes/uniaxial.ini | build
	@mkdir -p $(@D)
	@echo "dem-run uniaxial $* cells"
	@$(RUN_ENV) /usr/bin/time -f "%e %M" -o $(AC)/res/$*.time $(BIN)/dem-run --scene data/scenes/uniaxial.ini $< -q -o $@ \
	  --stop.t_max 5e-3 --output.frame_interval 1

$(AC)/res/%.row: $(AC)/res/%.h5
	@read -r wall mem < $(AC)/res/$*.time; cells=$$(echo $* | awk -Fx '{ print $$1 * $$2 }'); \
	steps=$$(h5dump -a /steps $< | awk '/\(0\)/ { print $$2 }'); \
	k=$$($(BIN)/observables $< --fit stress:axial_strain --after 3e-3 | awk '$$1 == "slope" { print $$2 }'); \
	echo "$*,$$cells,$$steps,$$wall,$$(awk -v m=$$mem 'BEGIN { printf "%.1f", m / 1024 }'),$$(awk -v c=$$cells -v s=$$steps -v w=$$wall 'BEGIN { printf "%.4g", c * s / (w > 0 ? w : 1e-3) }'),$$k" > $@

$(AC)/resolution.csv: $(foreach r,$(AC_RESOLUTIONS),$(AC)/res/$(r).row)
	@{ echo "cells_grid,cells,steps,wall_s,peak_MB,cell_steps_per_s,K_Pa,K_error_vs_finest"; \
	   cat $^ | awk -F, '{ row[NR] = $$0; k[NR] = $$7 } END { f = k[NR]; for (i = 1; i <= NR; i++) { d = (k[i] - f) / f; if (d < 0) d = -d; printf "%s,%.4g\n", row[i], d } }'; } > $@

$(AC)/table.md: $(AC)/timestep.csv $(AC)/orders.csv $(AC)/resolution.csv
	@{ echo "# What accuracy costs in time (polygon DEM)"; echo; \
	   echo "## Time step and integrator (300-cell disc, undamped pulse, E0 = 5 J, to t = 2e-4 s)"; echo; \
	   echo "| integrator | dt / bound | dt (s) | steps | wall (s) | peak (MB) | cell-steps/s | energy drift | rms displacement error (m) |"; \
	   echo "|---|---|---|---|---|---|---|---|---|"; \
	   awk -F, 'NR > 1 { printf "| %s | 2^-%s | %.3g | %s | %s | %s | %.3g | %.2g | %.2g |\n", $$1, $$2, $$3, $$4, $$5, $$6, $$7, $$8, $$9 }' $<; echo; \
	   echo "Observed order of convergence of the displacement (levels 3-6):"; echo; \
	   awk -F, 'NR > 1 { printf "- %s: %s\n", $$1, $$2 }' $(AC)/orders.csv; echo; \
	   echo "## Resolution (uniaxial tension, 0.25 m × 0.40 m, to t = 5e-3 s)"; echo; \
	   echo "| cells | steps | wall (s) | peak (MB) | cell-steps/s | K (Pa) | error vs finest |"; echo "|---|---|---|---|---|---|---|"; \
	   awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %.3g | %.4g | %.2g |\n", $$2, $$3, $$4, $$5, $$6, $$7, $$8 }' $(AC)/resolution.csv; } > $@

$(AC)/error-vs-time.png: $(AC)/timestep.csv pipelines/plots/accuracy.gp
	@gnuplot -e "csv='$<'; out='$(AC)/error-vs-time'" pipelines/plots/accuracy.gp

$(AC)/resolution.png: $(AC)/resolution.csv pipelines/plots/resolution.gp
	@gnuplot -e "csv='$<'; out='$(AC)/resolution'" pipelines/plots/resolution.gp
