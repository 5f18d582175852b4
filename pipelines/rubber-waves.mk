# rubber-waves (part of rubber-crack): long-wave speeds along the crack (x) versus the stretch across it,
# measured on Marder's lattice with a small plane pulse (data/scenes/wave.ini, periodic across the pulse)
# and predicted by the Mooney-Rivlin closed forms (wave-speed --theory), at λx = 1.2 as in the crack
# runs. The cut-off sits 0.9Δ (18 widths) above each state's far-field bonds, so the far field is
# Mooney-Rivlin (rubber-lattice-validation.md §D.1); the pulse is 20Δ wide (dispersion < 1%, docs/wave-speed.md).
#   make -f Makefile.analysis rubber-crack   (or only these: make -f Makefile.analysis rubber-waves)
RW := $(RESULTS)/rubber-crack/waves
# λy = 2 is left out: at (1.2, 2) the pre-stretched sheet gains energy from nothing (7.384 -> 7.385 J
# in 4 ms against a pulse of ~1e-6 J) and wave-speed finds no front (a lattice instability, not studied).
RW_STRETCHES ?= $(if $(MINI),3,2.5 3 3.5 4)
RW_NODES := $(if $(MINI),200x4,600x4)
RW_WIDTH := $(if $(MINI),1e-2,2e-2)
RW_MODES := longitudinal shear

.PHONY: rubber-waves
rubber-waves: $(RW).md $(RW).png
rubber-crack: $(RW).md $(RW).png

$(RW)/line.h5: | build
	@mkdir -p $(@D)
	$(LAUNCH) $(BIN)/mesh-gen triangular --nodes $(RW_NODES) --spacing 1e-3 -q -o $@

# speeds-<mode>-<λy>.txt: the pulse run piped into wave-speed (key value lines). The run lasts until the
# front has crossed the half strip (1.02 × half length / predicted speed), 150 frames.
$(RW)/speeds-%.txt: $(RW)/line.h5 data/scenes/wave.ini | build
	@IFS=- read -r mode ly <<< "$*"; echo "rubber-run wave $$mode λy = $$ly"; \
	c=$$($(BIN)/wave-speed --theory --a 1600 --b 1.5 --stretch 1.2x$$ly --direction x --format text | \
	  awk -v k=predicted.x.$$mode '$$1 == k { print $$2 }'); \
	half=$$(awk -v n=$(firstword $(subst x, ,$(RW_NODES))) 'BEGIN { print (n / 2 - 0.5) * 1e-3 * 1.2 }'); \
	tmax=$$(awk -v h=$$half -v c=$$c 'BEGIN { printf "%.6g", 1.02 * h / c }'); \
	uc=$$(awk -v l=$$ly 'BEGIN { printf "%.6g", 1e-3 * (sqrt(0.36 + 0.75 * l * l) + 0.9) }'); \
	$(RUN_ENV) $(LAUNCH) $(BIN)/rubber-run $(THREADS_OPT) --scene data/scenes/wave.ini $< --loading.stretch_y $$ly --law.cutoff_length $$uc \
	  --pulse.kind $$mode --pulse.width $(RW_WIDTH) --stop.t_max $$tmax \
	  --output.frame_interval $$(awk -v t=$$tmax 'BEGIN { printf "%.6g", t / 150 }') -q -o $(@:.txt=.h5); \
	$(BIN)/wave-speed $(@:.txt=.h5) --format text -q -o $@; rm -f $(@:.txt=.h5)

# One row per stretch: λy, then per mode the measured speed, its error, the prediction and the deviation.
$(RW).csv: $(foreach l,$(RW_STRETCHES),$(foreach m,$(RW_MODES),$(RW)/speeds-$(m)-$(l).txt))
	@{ echo "stretch_x,stretch_y,c_L_measured_m_s,c_L_error_m_s,c_L_predicted_m_s,c_L_deviation,c_T_measured_m_s,c_T_error_m_s,c_T_predicted_m_s,c_T_deviation,regime"; \
	   for ly in $(RW_STRETCHES); do \
	     l=$(RW)/speeds-longitudinal-$$ly.txt; s=$(RW)/speeds-shear-$$ly.txt; \
	     awk -v ly=$$ly 'FNR == 1 { f++ } { v[f, $$1] = $$2 } END { \
	       printf "1.2,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", ly, \
	         v[1, "measured.longitudinal.x.speed"], v[1, "measured.longitudinal.x.stderr"], v[1, "predicted.x.longitudinal"], v[1, "measured.longitudinal.x.deviation"], \
	         v[2, "measured.shear.x.speed"], v[2, "measured.shear.x.stderr"], v[2, "predicted.x.shear"], v[2, "measured.shear.x.deviation"], v[1, "lattice.regime"] }' $$l $$s; \
	   done; } > $@

$(RW).md: $(RW).csv
	@{ echo "# Wave speeds along x versus the stretch across the crack (λx = 1.2, a = 1600 m²/s², b = 1.5)"; echo; \
	   echo "Measured on the lattice (plane pulse, arrival times fitted) and predicted by Mooney-Rivlin; deviation = measured / predicted − 1."; echo; \
	   echo "| λy | c_L measured (m/s) | c_L predicted | deviation | c_T measured (m/s) | c_T predicted | deviation | lattice regime |"; \
	   echo "|---|---|---|---|---|---|---|---|"; \
	   awk -F, 'NR > 1 { printf "| %s | %.4g ± %.2g | %.4g | %+.2f %% | %.4g ± %.2g | %.4g | %+.2f %% | %s |\n", $$2, $$3, $$4, $$5, 100 * $$6, $$7, $$8, $$9, 100 * $$10, $$11 }' $<; } > $@

$(RW).png: $(RW).csv pipelines/plots/rubber-waves.gp
	@gnuplot -e "csv='$<'; out='$(RW)'" pipelines/plots/rubber-waves.gp
