// A command-line run is one job in a process of its own. V8's default tier-up budget,
// tuned for pages that run for long, sends every moderately hot function to the
// optimising compiler early, which in a run of a second costs more than it saves
// (fandisk/22: 0.57 → 0.44 s a run; a 650K-face run of 6 s unchanged). With a larger
// budget only the code that runs longest is optimised. It must be set before the module
// is compiled, which the next lines do.
require('v8').setFlagsFromString('--wasm-tiering-budget=200000000');
