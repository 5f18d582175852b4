# accuracy-cost: what accuracy costs in time (issue 7 §1), for both models (docs/accuracy-cost.md).
# Knobs, each swept while the others stay fixed; errors against a reference (the finest setting, or the
# continuum); cost as wall time (GNU time, whole process), the time loop alone, steps, cell- or
# node-steps per second of the loop, and peak memory (GNU time's maximum resident set).
#   DEM time step × integrator, on the smooth problem (the pulse scene with contacts off: beams only, no
#     breaking, damping or friction; 1100-cell disc, E0 = 500 J, to t = 0.2 ms): 7 levels from each
#     integrator's stability bound down by factors of 2; gear5 with the usual zero start and with the
#     exact start (integrator.start = exact), Verlet. Errors: rms displacement against gear5-exact at
#     2^-9 of its bound, energy drift. The observed order of each series.
#   DEM resolution: the uniaxial beam lattice (contacts off) from 10×16 to 100×160 cells, K against the
#     finest; the radial pulse front speed at three resolutions against the finest.
#   DEM fragmentation: the explosion scene (contacts and breaking on) on small discs, over seeds: β and
#     the largest fragment at three time steps (paired by seed) and three resolutions (300-1100 cells).
#   Rubber time step × integrator: the wave scene (cut-off off: a smooth elastic problem) on a
#     100×10 strip, 7 levels from each bound; errors against gear5 at 2^-8 of its bound, energy drift
#     against the pulse energy, wave speed against Mooney-Rivlin.
#   Rubber resolution: the same strip (0.16 m) at 160 to 16000 nodes, wave speed against Mooney-Rivlin.
#   make -f Makefile.analysis accuracy-cost [SEEDS='1 2 3'] [JOBS=2]
AC := $(RESULTS)/accuracy-cost
AC_SEEDS ?= $(SEEDS)
AC_LEVELS := $(if $(MINI),0 1 2,0 1 2 3 4 5 6)
# GNU time: elapsed wall seconds and peak resident set (kB) of the whole process.
AC_TIME = /usr/bin/time -f "%e %M" -o $(basename $@).time

# ---------------------------------------------------------------- DEM: time step and integrator
AC_DEM_CELLS := $(if $(MINI),300,1100)
AC_DEM_T := 2e-4
AC_DEM_SERIES := gear5-zero gear5-exact verlet-zero
AC_DEM_REF := gear5-exact-$(if $(MINI),5,9)
AC_DEM_SMOOTH := --physics.contacts off --stop.t_max $(AC_DEM_T) --output.frame_interval 1 --output.observe_every 5

$(AC)/dem/disc.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.4 --cells $(AC_DEM_CELLS) --seed 1 -q -o $@

# bound-<integrator>.txt: "dt_bound omega_max" of the smooth problem, from a one-step run (kept: its final
# positions, one step after the kick, are the start the displacement scale is measured from).
$(AC)/dem/bound-%.txt: $(AC)/dem/disc.h5 data/scenes/pulse.ini | build
	@$(RUN_ENV) $(LAUNCH) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/pulse.ini $< -q -o $(AC)/dem/bound-$*.h5 $(AC_DEM_SMOOTH) \
	  --integrator.kind $* --integrator.dt auto --stop.max_steps 1
	@echo "$$($(BIN)/observables $(AC)/dem/bound-$*.h5 --parameter derived.dt_bound) \
	  $$($(BIN)/observables $(AC)/dem/bound-$*.h5 --parameter derived.omega_max)" > $@

# dem/dt/<integrator>-<start>-<level>.h5: n = ceil(T/bound)·2^level steps of dt = T/n, so that every run
# ends exactly at T (the displacement error is compared at one time).
.SECONDEXPANSION:
$(AC)/dem/dt/%.h5: $(AC)/dem/disc.h5 $$(AC)/dem/bound-$$(firstword $$(subst -, ,$$*)).txt data/scenes/pulse.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r kind start level <<< "$*"; \
	n=$$(awk -v T=$(AC_DEM_T) -v l=$$level '{ n = int(T / $$1); if (n * $$1 < T) n++; printf "%d", n * 2 ^ l }' $(word 2,$^)); \
	dt=$$(awk -v T=$(AC_DEM_T) -v n=$$n 'BEGIN { printf "%.17g", T / n }'); \
	echo "dem-run pulse, beams only: $$kind, $$start start, 2^-$$level of the bound ($$n steps)"; \
	$(RUN_ENV) $(LAUNCH) $(AC_TIME) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/pulse.ini $< -q -o $@ $(AC_DEM_SMOOTH) \
	  --integrator.kind $$kind --integrator.start $$start --integrator.dt $$dt --stop.max_steps $$n

# One row per run: series,integrator,start,level,dt_s,omega_dt,steps,wall_s,loop_s,peak_MB,cell_steps_per_s,
# energy_drift,rms_displacement_error_m,max_displacement_error_m,wave_speed_deviation (rubber only).
$(AC)/dem/dt/%.row: $(AC)/dem/dt/%.h5 $(AC)/dem/dt/$(AC_DEM_REF).h5
	@IFS=- read -r kind start level <<< "$*"; read -r wall mem < $(AC)/dem/dt/$*.time; \
	read -r bound omega < $(AC)/dem/bound-$$kind.txt; \
	dt=$$($(BIN)/observables $< --parameter derived.dt); \
	steps=$$(h5dump -a /steps $< | awk '/\(0\)/ { print $$2 }'); loop=$$(h5dump -a /provenance/wall_seconds $< | awk '/\(0\)/ { print $$2 }'); \
	cells=$$(h5ls $</particles/cells/mass | sed 's/.*{\([0-9]*\)}.*/\1/'); \
	drift=$$($(BIN)/observables $< --columns energy_balance | grep -v "^#" | \
	  awk -F, 'NR == 2 { e0 = $$2 } NR > 1 { d = $$2 - e0; if (d < 0) d = -d; if (d > m) m = d } END { printf "%.4g", m / e0 }'); \
	err=$$($(BIN)/observables $< --compare $(word 2,$^) | awk '$$1 == "rms_position_difference" { r = $$2 } $$1 == "max_position_difference" { m = $$2 } END { print r "," m }'); \
	echo "$$kind-$$start,$$kind,$$start,$$level,$$dt,$$(awk -v o=$$omega -v d=$$dt 'BEGIN { printf "%.4g", o * d }'),$$steps,$$wall,$$loop,$$(awk -v m=$$mem 'BEGIN { printf "%.1f", m / 1024 }'),$$(awk -v c=$$cells -v s=$$steps -v w=$$loop 'BEGIN { printf "%.4g", c * s / (w > 0 ? w : 1e-6) }'),$$drift,$$err," > $@

AC_TIMESTEP_HEADER := series,integrator,start,level,dt_s,omega_dt,steps,wall_s,loop_s,peak_MB,cell_steps_per_s,energy_drift,rms_displacement_error_m,max_displacement_error_m,wave_speed_deviation

$(AC)/dem-timestep.csv: $(foreach s,$(AC_DEM_SERIES),$(foreach l,$(AC_LEVELS),$(AC)/dem/dt/$(s)-$(l).row))
	@{ echo "$(AC_TIMESTEP_HEADER)"; cat $^; } > $@

# The rms displacement of the pulse at T (the scale of the errors): the reference against the one-step run.
$(AC)/dem/displacement.txt: $(AC)/dem/dt/$(AC_DEM_REF).h5 $(AC)/dem/bound-gear5.txt
	@$(BIN)/observables $< --compare $(AC)/dem/bound-gear5.h5 | awk '$$1 == "rms_position_difference" { print $$2 }' > $@

# Observed order of each series: least-squares slope of log(error) against log(dt) over the levels whose
# error is at least 30 times the rounding floor (the smallest error measured in the table: the exact
# start reaches it), and the same for the energy drift; "n/a" with fewer than two such levels.
AC_ORDERS_AWK := NR > 1 && $$13 > 0 { n++; s[n] = $$1; x[n] = log($$5); e[n] = $$13; d[n] = $$12; \
	  if (fe == "" || $$13 < fe) fe = $$13; if (fd == "" || ($$12 > 0 && $$12 < fd)) fd = $$12 } \
	END { print "series,observed_order_displacement,levels_displacement,observed_order_energy,levels_energy"; \
	  for (i = 1; i <= n; i++) if (!(s[i] in seen)) { seen[s[i]] = 1; order[++m] = s[i] } \
	  for (k = 1; k <= m; k++) { printf "%s", order[k]; fit(order[k], e, fe); fit(order[k], d, fd); printf "\n" } } \
	function fit(name, y, floor,   i, c, sx, sy, sxx, sxy) { c = 0; sx = sy = sxx = sxy = 0; \
	  for (i = 1; i <= n; i++) if (s[i] == name && y[i] >= 30 * floor) { c++; sx += x[i]; sy += log(y[i]); sxx += x[i] * x[i]; sxy += x[i] * log(y[i]) } \
	  if (c >= 2) printf ",%.2f,%d", (c * sxy - sx * sy) / (c * sxx - sx * sx), c; else printf ",n/a,%d", c }

$(AC)/dem-orders.csv: $(AC)/dem-timestep.csv
	@awk -F, '$(AC_ORDERS_AWK)' $< > $@

# ---------------------------------------------------------------- DEM: resolution
# The beam lattice (contacts off, so no damping either) of a 0.25 m × 0.40 m sample pulled at 0.02 m/s
# per side to t = 10 ms (strain 1e-3); K = slope of σ(ε) after 3 ms (ringing averages out over 7 ms).
AC_DEM_GRIDS := $(if $(MINI),10x16 20x32,10x16 20x32 25x40 40x64 60x96 100x160)
AC_DEM_UNIAXIAL := --physics.contacts off --physics.damping off --stop.t_max $(if $(MINI),4e-3,1e-2) --output.frame_interval 1

$(AC)/dem/res/mesh-%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape rect --size 0.25x0.40 --cells $* --seed 1 -q -o $@

$(AC)/dem/res/%.h5: $(AC)/dem/res/mesh-%.h5 data/scenes/uniaxial.ini | build
	@echo "dem-run uniaxial beam lattice, $* cells"
	@$(RUN_ENV) $(LAUNCH) $(AC_TIME) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/uniaxial.ini $< -q -o $@ $(AC_DEM_UNIAXIAL)

$(AC)/dem/res/%.row: $(AC)/dem/res/%.h5
	@read -r wall mem < $(AC)/dem/res/$*.time; cells=$$(h5ls $</particles/cells/mass | sed 's/.*{\([0-9]*\)}.*/\1/'); \
	steps=$$(h5dump -a /steps $< | awk '/\(0\)/ { print $$2 }'); loop=$$(h5dump -a /provenance/wall_seconds $< | awk '/\(0\)/ { print $$2 }'); \
	dt=$$($(BIN)/observables $< --parameter derived.dt); \
	k=$$($(BIN)/observables $< --fit stress:axial_strain --after $(if $(MINI),2e-3,3e-3) | awk '$$1 == "slope" { s = $$2 } $$1 == "slope_stderr" { e = $$2 } END { print s "," e }'); \
	echo "$*,$$cells,$$steps,$$dt,$$wall,$$loop,$$(awk -v m=$$mem 'BEGIN { printf "%.1f", m / 1024 }'),$$(awk -v c=$$cells -v s=$$steps -v w=$$loop 'BEGIN { printf "%.4g", c * s / (w > 0 ? w : 1e-6) }'),$$k" > $@

$(AC)/dem-resolution.csv: $(foreach r,$(AC_DEM_GRIDS),$(AC)/dem/res/$(r).row)
	@{ echo "grid,cells,steps,dt_s,wall_s,loop_s,peak_MB,cell_steps_per_s,K_Pa,K_stderr_Pa,K_error_vs_finest"; \
	   cat $^ | awk -F, '{ row[NR] = $$0; k[NR] = $$9 } END { f = k[NR]; for (i = 1; i <= NR; i++) { d = (k[i] - f) / f; if (d < 0) d = -d; printf "%s,%.4g\n", row[i], d } }'; } > $@

# The radial front of the pulse (beams only, E0 = 5 J: linear) on discs of 0.4 m, its speed by wave-speed
# (arrival of half the local peak displacement, fitted over distance) against the finest disc.
AC_DEM_WAVE_CELLS := $(if $(MINI),300 600,300 1100 4400)

$(AC)/dem/wave/mesh-%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.4 --cells $* --seed 1 -q -o $@

$(AC)/dem/wave/%.h5: $(AC)/dem/wave/mesh-%.h5 data/scenes/pulse.ini | build
	@echo "dem-run pulse, beams only, $* cells"
	@$(RUN_ENV) $(LAUNCH) $(AC_TIME) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/pulse.ini $< -q -o $@ \
	  --physics.contacts off --loading.energy 5 --stop.t_max 4e-4 --output.frame_interval 1e-5 --integrator.dt auto

$(AC)/dem/wave/%.row: $(AC)/dem/wave/%.h5
	@read -r wall mem < $(AC)/dem/wave/$*.time; cells=$$(h5ls $</particles/cells/mass | sed 's/.*{\([0-9]*\)}.*/\1/'); \
	steps=$$(h5dump -a /steps $< | awk '/\(0\)/ { print $$2 }'); \
	c=$$($(BIN)/wave-speed $< --mode longitudinal --format text 2>/dev/null | \
	  awk '$$1 ~ /^measured\.longitudinal\..*\.speed$$/ { s = $$2 } $$1 ~ /^measured\.longitudinal\..*\.stderr$$/ { e = $$2 } $$1 ~ /^measured\.longitudinal\..*\.points$$/ { p = $$2 } END { print s "," e "," p }'); \
	echo "$$cells,$$steps,$$wall,$$(awk -v m=$$mem 'BEGIN { printf "%.1f", m / 1024 }'),$$c" > $@

$(AC)/dem-wavespeed.csv: $(foreach c,$(AC_DEM_WAVE_CELLS),$(AC)/dem/wave/$(c).row)
	@{ echo "cells,steps,wall_s,peak_MB,c_L_m_per_s,c_L_stderr_m_per_s,points,deviation_vs_finest,deviation_sigma"; \
	   cat $^ | awk -F, '{ row[NR] = $$0; c[NR] = $$5; e[NR] = $$6 } END { for (i = 1; i <= NR; i++) { d = (c[i] - c[NR]) / c[NR]; \
	     s = sqrt(e[i] ^ 2 + (i < NR ? e[NR] ^ 2 : 0)) / c[NR]; printf "%s,%.3g,%.3g\n", row[i], d, s } }'; } > $@

# ---------------------------------------------------------------- DEM: fragmentation over seeds
# The explosion scene (contacts, breaking; E0 = 500 J) on 0.4 m discs: settings <cells>-<dt in ns>.
# The seed is the mesh's: at one cell count every dt runs on the same meshes, so the differences between
# time steps are paired by seed and free of seed-to-seed scatter; across cell counts they are not.
AC_FRAG_SETTINGS := $(if $(MINI),300-1000 300-500,300-1000 300-500 300-250 600-1000 1100-1000)
AC_FRAG_OPTIONS := $(if $(MINI),--stop.t_max 1e-3 --output.frame_interval 5e-4,--output.frame_interval 1e-3)
AC_FRAG_FIT := --bootstrap 0 --gof-samples 0 --no-compare $(if $(MINI),--min-tail 5,)

$(AC)/frag/mesh-%.h5: | build
	@mkdir -p $(@D)
	@IFS=- read -r cells seed <<< "$*"; \
	$(LAUNCH) $(BIN)/mesh-gen voronoi --shape disc --diameter 0.40 --cells $$cells --seed $${seed#s} -q -o $@

# frag/runs/<cells>-<dt_ns>-s<seed>.h5
$(AC)/frag/runs/%.h5: $$(AC)/frag/mesh-$$(firstword $$(subst -, ,$$*))-$$(lastword $$(subst -, ,$$*)).h5 data/scenes/explosion.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r cells ns seed <<< "$*"; echo "dem-run explosion $$cells cells, dt = $$ns ns, $$seed"; \
	$(RUN_ENV) $(LAUNCH) $(AC_TIME) $(BIN)/dem-run $(THREADS_OPT) --scene data/scenes/explosion.ini $< -q -o $@ $(AC_FRAG_OPTIONS) \
	  --integrator.dt $$(awk -v ns=$$ns 'BEGIN { printf "%.17g", ns * 1e-9 }')

$(AC)/frag/runs/%.frag.h5: $(AC)/frag/runs/%.h5
	@$(BIN)/fragment-count $< --min-cells 2 -q -o $@

# One row per run: cells (nominal),cells_actual,dt_s,seed,steps,wall_s,peak_MB,fragments (all, single cells
# included),beta,beta_stderr,n_tail,largest_kg,largest_fraction (of the disc's mass)
$(AC)/frag/runs/%.row: $(AC)/frag/runs/%.frag.h5 $(AC)/frag/runs/%.h5
	@IFS=- read -r cells ns seed <<< "$*"; read -r wall mem < $(AC)/frag/runs/$*.time; \
	steps=$$(h5dump -a /steps $(word 2,$^) | awk '/\(0\)/ { print $$2 }'); \
	fit=$$($(BIN)/powerlaw-fit $< --column mass $(AC_FRAG_FIT) --format text -q 2>/dev/null | \
	  awk '$$1 == "alpha" { a = $$2 } $$1 == "alpha_stderr" { e = $$2 } $$1 == "n_tail" { t = $$2 } END { print a "," e "," t }'); \
	masses=$$(h5dump -y -w 0 -d /fragments/mass $< | awk '/^ *DATA [{]/ && !done { on = 1; next } on && /[}]/ { on = 0; done = 1 } on { gsub(/,/, " "); \
	  for (i = 1; i <= NF; i++) { x = $$i + 0; n++; s += x; if (x > m) m = x } } END { printf "%d,%.6g,%.4g", n, m, m / s }'); \
	echo "$$cells,$$(h5ls $(word 2,$^)/particles/cells/mass | sed 's/.*{\([0-9]*\)}.*/\1/'),$$(awk -v ns=$$ns 'BEGIN { printf "%.3g", ns * 1e-9 }'),$${seed#s},$$steps,$$wall,$$(awk -v m=$$mem 'BEGIN { printf "%.1f", m / 1024 }'),$$(echo $$masses | cut -d, -f1),$$fit,$$(echo $$masses | cut -d, -f2,3)" > $@

AC_FRAG_RUNS := $(foreach p,$(AC_FRAG_SETTINGS),$(foreach s,$(AC_SEEDS),$(AC)/frag/runs/$(p)-s$(s).row))

$(AC)/fragmentation-runs.csv: $(AC_FRAG_RUNS)
	@{ echo "cells,cells_actual,dt_s,seed,steps,wall_s,peak_MB,fragments,beta,beta_stderr,n_tail,largest_kg,largest_fraction"; cat $^; } > $@

# Per setting: mean and seed-to-seed standard deviation of β and of the largest fragment's share of the
# mass; the discretisation effect as the difference from the finest dt at the same cells (paired by seed:
# mean ± sd of the per-seed differences) and from the most cells at the same dt (unpaired: difference of
# the means ± its standard error).
$(AC)/fragmentation.csv: $(AC)/fragmentation-runs.csv
	@awk -F, 'NR > 1 { k = $$1 "," $$3; if (!(k in n)) key[++m] = k; n[k]++; b[k, n[k]] = $$9; f[k, n[k]] = $$13; sd[k, n[k]] = $$4; \
	    w[k] += $$6; fe[k] += $$10; cells[k] = $$1; dt[k] = $$3; \
	    if (!($$1 in finest) || $$3 + 0 < finest[$$1] + 0) finest[$$1] = $$3; if (!($$3 in most) || $$1 + 0 > most[$$3] + 0) most[$$3] = $$1 } \
	  function mean(k, a,   i, s) { s = 0; for (i = 1; i <= n[k]; i++) s += a[k, i]; return s / n[k] } \
	  function sdev(k, a,   i, s, mu) { if (n[k] < 2) return 0; mu = mean(k, a); s = 0; for (i = 1; i <= n[k]; i++) s += (a[k, i] - mu) ^ 2; return sqrt(s / (n[k] - 1)) } \
	  function paired(k, r, a,   i, j, c, s, ss, d) { c = 0; s = ss = 0; for (i = 1; i <= n[k]; i++) for (j = 1; j <= n[r]; j++) if (sd[k, i] == sd[r, j]) { d = a[k, i] - a[r, j]; c++; s += d; ss += d * d } \
	    if (c < 1) return "n/a,n/a"; return sprintf("%.3g,%.3g", s / c, c > 1 ? sqrt((ss - s * s / c) / (c - 1)) : 0) } \
	  function unpaired(k, r, a) { return sprintf("%.3g,%.3g", mean(k, a) - mean(r, a), sqrt(sdev(k, a) ^ 2 / n[k] + sdev(r, a) ^ 2 / n[r])) } \
	  END { print "cells,dt_s,seeds,wall_s_per_run,beta_mean,beta_sd_seeds,beta_fit_stderr,dbeta_vs_finest_dt,dbeta_vs_finest_dt_sd_paired,dbeta_vs_most_cells,dbeta_vs_most_cells_stderr,largest_fraction_mean,largest_fraction_sd_seeds,dlargest_vs_finest_dt,dlargest_vs_finest_dt_sd_paired,dlargest_vs_most_cells,dlargest_vs_most_cells_stderr"; \
	    for (i = 1; i <= m; i++) { k = key[i]; rd = cells[k] "," finest[cells[k]]; rc = most[dt[k]] "," dt[k]; \
	      printf "%s,%s,%d,%.3g,%.4g,%.3g,%.3g,%s,%s,%.4g,%.3g,%s,%s\n", cells[k], dt[k], n[k], w[k] / n[k], mean(k, b), sdev(k, b), fe[k] / n[k], \
	        (rd == k ? "0,0" : paired(k, rd, b)), (rc == k ? "0,0" : unpaired(k, rc, b)), mean(k, f), sdev(k, f), \
	        (rd == k ? "0,0" : paired(k, rd, f)), (rc == k ? "0,0" : unpaired(k, rc, f)) } }' $< > $@

# ---------------------------------------------------------------- rubber: time step and integrator
# The wave scene on a strip 0.16 m long (reference length, x; periodic in y) at (λx, λy) = (1.2, 3): a
# Gaussian pulse of width 4 mm and amplitude 0.1 mm (strain ~2.5%, linear) from the middle, to
# t = 0.6 ms (the fronts run 76 mm of the 96 mm to the clamped ends). The cut-off is off: nothing comes
# near u_c, and with it on the bound would be set by a bond passing through it (10.4 times smaller here).
# Law lengths scale with the spacing Δ = 0.16 m / nx: u_s = 0.1Δ (u_c = 3.45Δ, width 0.05Δ, unused).
AC_RUB_T := 6e-4
AC_RUB_DT_MESH := $(if $(MINI),40x4,100x10)
AC_RUB_REF := gear5-$(if $(MINI),4,8)
AC_RUB_PULSE := --pulse.width 4e-3 --pulse.amplitude 1e-4 --stop.t_max $(AC_RUB_T) --output.frame_interval 5e-6 --output.observe_every 10
# wave-speed: fit the arrivals between 4 widths from the source (outside the initial pulse) and 0.9 c_L·T.
AC_RUB_RANGE := 0.016:0.066
ac_rubber_law = $$(awk -v n=$$(echo $(1) | cut -dx -f1) 'BEGIN { d = 0.16 / n; \
	printf "--law.cutoff none --law.short_width %.6g --law.cutoff_length %.6g --law.cutoff_width %.6g", 0.1 * d, 3.45 * d, 0.05 * d }')

$(AC)/rubber/mesh-%.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen triangular --nodes $* --spacing $$(awk -v n=$$(echo $* | cut -dx -f1) 'BEGIN { printf "%.6g", 0.16 / n }') -q -o $@

$(AC)/rubber/bound-%.txt: $(AC)/rubber/mesh-$(AC_RUB_DT_MESH).h5 data/scenes/wave.ini | build
	@$(RUN_ENV) $(LAUNCH) $(BIN)/rubber-run $(THREADS_OPT) --scene data/scenes/wave.ini $< -q -o $(AC)/rubber/bound-$*.h5 \
	  $(call ac_rubber_law,$(AC_RUB_DT_MESH)) $(AC_RUB_PULSE) --integrator.kind $* --stop.max_steps 1
	@echo "$$($(BIN)/observables $(AC)/rubber/bound-$*.h5 --parameter derived.dt_bound) \
	  $$($(BIN)/observables $(AC)/rubber/bound-$*.h5 --parameter derived.omega_max)" > $@
	@rm -f $(AC)/rubber/bound-$*.h5

# rubber/dt/<integrator>-<level>.h5 (rubber-run has no exact start: gear5 starts from zero). Not quiet:
# the last line of the log gives the time loop's wall time.
$(AC)/rubber/dt/%.h5: $(AC)/rubber/mesh-$(AC_RUB_DT_MESH).h5 $$(AC)/rubber/bound-$$(firstword $$(subst -, ,$$*)).txt data/scenes/wave.ini | build
	@mkdir -p $(@D)
	@IFS=- read -r kind level <<< "$*"; \
	n=$$(awk -v T=$(AC_RUB_T) -v l=$$level '{ n = int(T / $$1); if (n * $$1 < T) n++; printf "%d", n * 2 ^ l }' $(word 2,$^)); \
	dt=$$(awk -v T=$(AC_RUB_T) -v n=$$n 'BEGIN { printf "%.17g", T / n }'); \
	echo "rubber-run wave, $$kind, 2^-$$level of the bound ($$n steps)"; \
	$(RUN_ENV) $(LAUNCH) $(AC_TIME) $(BIN)/rubber-run $(THREADS_OPT) --scene data/scenes/wave.ini $< -o $@ \
	  $(call ac_rubber_law,$(AC_RUB_DT_MESH)) $(AC_RUB_PULSE) --integrator.kind $$kind --integrator.dt $$dt --stop.max_steps $$n 2> $(basename $@).log

# Energy drift: max |E(t) − E(0)| over the pulse energy 2·E_kin(T) (a travelling wave carries as much
# kinetic as elastic energy; the pre-stretch energy of the sheet, 10^5 times larger, is left out).
AC_RUB_DRIFT := awk -F, 'NR == 2 { e0 = $$3 } NR > 1 { d = $$3 - e0; if (d < 0) d = -d; if (d > m) m = d; k = $$2 } END { printf "%.4g", m / (2 * k) }'
AC_RUB_SPEED := awk '$$1 == "measured.longitudinal.x.speed" { s = $$2 } $$1 == "measured.longitudinal.x.stderr" { e = $$2 } \
	$$1 == "measured.longitudinal.x.predicted" { p = $$2 } $$1 == "measured.longitudinal.x.deviation" { d = $$2 } END { print s "," e "," p "," d }'

$(AC)/rubber/dt/%.row: $(AC)/rubber/dt/%.h5 $(AC)/rubber/dt/$(AC_RUB_REF).h5
	@IFS=- read -r kind level <<< "$*"; read -r wall mem < $(AC)/rubber/dt/$*.time; \
	read -r bound omega < $(AC)/rubber/bound-$$kind.txt; \
	dt=$$($(BIN)/observables $< --parameter derived.dt); \
	steps=$$(h5dump -a /steps $< | awk '/\(0\)/ { print $$2 }'); \
	loop=$$(grep -o '[0-9.e+-]* s wall' $(AC)/rubber/dt/$*.log | tail -1 | cut -d' ' -f1); \
	nodes=$$(h5ls $</particles/nodes/mass | sed 's/.*{\([0-9]*\)}.*/\1/'); \
	drift=$$($(BIN)/observables $< --columns kinetic_energy,total_energy | grep -v "^#" | $(AC_RUB_DRIFT)); \
	err=$$($(BIN)/observables $< --compare $(word 2,$^) | awk '$$1 == "rms_position_difference" { r = $$2 } $$1 == "max_position_difference" { m = $$2 } END { print r "," m }'); \
	dev=$$($(BIN)/wave-speed $< --range $(AC_RUB_RANGE) --format text 2>/dev/null | $(AC_RUB_SPEED) | cut -d, -f4); \
	echo "$$kind-zero,$$kind,zero,$$level,$$dt,$$(awk -v o=$$omega -v d=$$dt 'BEGIN { printf "%.4g", o * d }'),$$steps,$$wall,$$loop,$$(awk -v m=$$mem 'BEGIN { printf "%.1f", m / 1024 }'),$$(awk -v c=$$nodes -v s=$$steps -v w=$$loop 'BEGIN { printf "%.4g", c * s / (w > 0 ? w : 1e-6) }'),$$drift,$$err,$$dev" > $@

$(AC)/rubber-timestep.csv: $(foreach k,gear5 verlet,$(foreach l,$(AC_LEVELS),$(AC)/rubber/dt/$(k)-$(l).row))
	@{ echo "$(AC_TIMESTEP_HEADER)"; cat $^; } > $@

$(AC)/rubber-orders.csv: $(AC)/rubber-timestep.csv
	@awk -F, '$(AC_ORDERS_AWK)' $< > $@

# ---------------------------------------------------------------- rubber: resolution
# The same strip and pulse at Δ = 4 mm (1 pulse width) to 0.4 mm (10 widths): 160 to 16000 nodes, each
# at the default step (0.5 of the Verlet bound); the wave speed against Mooney-Rivlin at (1.2, 3).
AC_RUB_MESHES := $(if $(MINI),40x4 100x10,40x4 63x6 100x10 200x20 400x40)

$(AC)/rubber/res/%.h5: $(AC)/rubber/mesh-%.h5 data/scenes/wave.ini | build
	@mkdir -p $(@D)
	@echo "rubber-run wave, $* nodes"
	@$(RUN_ENV) $(LAUNCH) $(AC_TIME) $(BIN)/rubber-run $(THREADS_OPT) --scene data/scenes/wave.ini $< -o $@ \
	  $(call ac_rubber_law,$*) $(AC_RUB_PULSE) 2> $(basename $@).log

$(AC)/rubber/res/%.row: $(AC)/rubber/res/%.h5
	@read -r wall mem < $(AC)/rubber/res/$*.time; \
	nodes=$$(h5ls $</particles/nodes/mass | sed 's/.*{\([0-9]*\)}.*/\1/'); \
	steps=$$(h5dump -a /steps $< | awk '/\(0\)/ { print $$2 }'); \
	loop=$$(grep -o '[0-9.e+-]* s wall' $(AC)/rubber/res/$*.log | tail -1 | cut -d' ' -f1); \
	drift=$$($(BIN)/observables $< --columns kinetic_energy,total_energy | grep -v "^#" | $(AC_RUB_DRIFT)); \
	speed=$$($(BIN)/wave-speed $< --range $(AC_RUB_RANGE) --format text 2>/dev/null | $(AC_RUB_SPEED)); \
	echo "$*,$$nodes,$$($(BIN)/observables $< --parameter derived.spacing),$$steps,$$($(BIN)/observables $< --parameter derived.dt),$$wall,$$loop,$$(awk -v m=$$mem 'BEGIN { printf "%.1f", m / 1024 }'),$$(awk -v c=$$nodes -v s=$$steps -v w=$$loop 'BEGIN { printf "%.4g", c * s / (w > 0 ? w : 1e-6) }'),$$drift,$$speed" > $@

$(AC)/rubber-resolution.csv: $(foreach r,$(AC_RUB_MESHES),$(AC)/rubber/res/$(r).row)
	@{ echo "grid,nodes,spacing_m,steps,dt_s,wall_s,loop_s,peak_MB,node_steps_per_s,energy_drift,c_L_m_per_s,c_L_stderr_m_per_s,c_L_mooney_rivlin_m_per_s,deviation"; cat $^; } > $@

# ---------------------------------------------------------------- table, recommendations and plot
AC_CSV := $(AC)/dem-timestep.csv $(AC)/dem-orders.csv $(AC)/dem-resolution.csv $(AC)/dem-wavespeed.csv \
	$(AC)/fragmentation-runs.csv $(AC)/fragmentation.csv $(AC)/rubber-timestep.csv $(AC)/rubber-orders.csv \
	$(AC)/rubber-resolution.csv

.PHONY: accuracy-cost
accuracy-cost: $(AC)/table.md $(AC)/error-vs-time.png
	@cat $(AC)/table.md

$(AC)/table.md: $(AC_CSV) $(AC)/dem/displacement.txt scripts/accuracy-cost-table.sh
	@bash scripts/accuracy-cost-table.sh $(AC) "$(AC_SEEDS)" $(JOBS) > $@

$(AC)/error-vs-time.png: $(AC_CSV) pipelines/plots/accuracy.gp
	@gnuplot -e "dir='$(AC)'; out='$(AC)/error-vs-time'" pipelines/plots/accuracy.gp
