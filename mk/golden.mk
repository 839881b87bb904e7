# Golden-vector runner: one program over every registered stage.
GOLDEN_COMMON := tests/golden/golden_common.c tests/golden/tdc_content.c
GOLDEN_OBJS = $(patsubst %.c,$(B)/%.o,$(GOLDEN_COMMON) $(foreach s,$(GOLDEN_STAGES),tests/golden/golden_$(s).c))

$(GEN)/golden_list.h: Makefile $(wildcard mk/*.mk) | $(GEN)
	@{ echo '/* generated: registered golden stages */'; echo '#define TDC_GOLDEN_LIST(X) \'; \
	   $(foreach s,$(GOLDEN_STAGES),echo '    X($(s)) \';) echo ''; } > $@.tmp
	@cmp -s $@.tmp $@ || mv $@.tmp $@; rm -f $@.tmp

$(B)/tests/golden/golden_host_main.o: $(GEN)/golden_list.h

# The runner's link rule is in the top-level Makefile, after every fragment
# is read, so stages registered by fragments sorting after this one are in.

$(B)/golden-check: $(B)/tests/tdc_golden tests/golden/check.sh
	@printf '#!/bin/sh\nexec tests/golden/check.sh "%s" -- %s\n' "$(VARIANT)" "$(B)/tests/tdc_golden" > $@
	@chmod +x $@

# Deliberate update (see docs/golden-vectors.md): regenerates the expected
# file of each stage from the gcc -O2 host build.
golden-update: $(B)/tests/tdc_golden
	@for s in $(GOLDEN_STAGES); do \
	    { echo "# golden checksums of stage $$s: stage/vector frame fnv1a64"; \
	      echo "# regenerate only deliberately: make golden-update, and say why in the commit"; \
	      $(B)/tests/tdc_golden $$s; } > tests/golden/$$s.expected; \
	    echo "wrote tests/golden/$$s.expected ($$(grep -vc '^#' tests/golden/$$s.expected) lines)"; done
