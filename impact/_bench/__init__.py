"""The work-precision benchmark behind `impact bench`: what each digit of accuracy costs in time,
for every way `impact` integrates an impact (entry point: `work_precision.run`)."""
