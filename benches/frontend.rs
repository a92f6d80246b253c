//! Front-end speed: lex + parse + compile of a generated 100,000-line program, in the plain
//! form and as the PG listing `awl dump --listing` writes of it (statement addresses, segment
//! headings). Target: at least 2 million lines per second on the plain form, in release
//! mode; the listing's rate is reported. `awl check` without `--cpu` (the same compile, and
//! the profiles it compiles on) is measured beside it.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};

use awl::frontend;
use awl::profile;

mod generated;
use generated::generate;

fn bench_front_end(c: &mut Criterion) {
    let cpu = profile::find("sinumerik-840c").unwrap();
    let source = generate(100_000);
    let lines = source.lines().count();
    let built = frontend::build_text("gen.awl", &source, cpu);
    assert!(
        built.diagnostics.is_empty(),
        "{:?}",
        built.diagnostics.first()
    );
    let mut group = c.benchmark_group("front_end");
    group.throughput(Throughput::Elements(lines as u64));
    group.sample_size(20);
    group.bench_function("lex_parse_compile_100k_lines", |b| {
        b.iter(|| frontend::build_text("gen.awl", &source, cpu))
    });
    // `awl check` without `--cpu`: the same compile, and the profiles it compiles on.
    group.bench_function("check_without_cpu_100k_lines", |b| {
        b.iter(|| {
            let built = frontend::build_text("gen.awl", &source, cpu);
            let language = frontend::Language::default();
            frontend::profiles_without_errors(&built, &built.sources, &[], language)
        })
    });
    group.finish();

    let listing = awl::dump::listing::listing(&built);
    let listed = frontend::build_text("gen_listing.awl", &listing, cpu);
    assert!(!listed.has_errors(), "{:?}", listed.diagnostics.first());
    let mut group = c.benchmark_group("front_end_listing");
    group.throughput(Throughput::Elements(listing.lines().count() as u64));
    group.sample_size(20);
    group.bench_function("lex_parse_compile_listing", |b| {
        b.iter(|| frontend::build_text("gen_listing.awl", &listing, cpu))
    });
    group.finish();
}

criterion_group!(benches, bench_front_end);
criterion_main!(benches);
