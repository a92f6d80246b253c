//! Front-end speed: lex + parse + compile of a generated 100,000-line program, in the plain
//! form and as the PG listing `awl dump --listing` writes of it (statement addresses, segment
//! headings). Target: at least 2 million lines per second on the plain form, in release
//! mode; the listing's rate is reported. `awl check` without `--cpu` (the same compile, and
//! the profiles it compiles on) is measured beside it.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};

use awl::frontend;
use awl::profile;

/// A program of realistic shape: PBs of bit logic, word arithmetic and timers, FBs with
/// parameters and labels, calls with parameter lines, and data blocks.
fn generate(lines: usize) -> String {
    let mut out = String::with_capacity(lines * 20);
    let mut count = 0;
    let mut block = 0u32;
    while count < lines {
        block += 1;
        // Each block type has its own numbers 0…255; three types keep 100k lines unique.
        let number = block / 3 % 256;
        match block % 3 {
            0 => {
                out.push_str(&format!("FB {number}\nNAME :GEN{number}\nDES  :EIN  I BI\nDES  :AUS  Q BI\nDES  :WERT D KF\n"));
                count += 5;
                for i in 0..30 {
                    out.push_str(&format!(
                        "      A  =EIN\n      JC =M{i:03}\n      L  =WERT\n      L  FW {}\n      +F\n      T  FW {}\nM{i:03} :R  =AUS\n",
                        i * 2 % 200,
                        (i * 2 + 2) % 200
                    ));
                    count += 7;
                }
            }
            1 => {
                out.push_str(&format!("PB {number}\n"));
                count += 1;
                for i in 0..40 {
                    out.push_str(&format!(
                        "      A  I {}.{}\n      AN F {}.{}\n      O  Q {}.{}\n      =  Q {}.{}\n      L  KT 050.1\n      SD T {}\n",
                        i % 100, i % 8, (i + 3) % 200, (i + 1) % 8, i % 100, (i + 2) % 8, (i + 4) % 100, (i + 5) % 8, i % 200
                    ));
                    count += 6;
                }
            }
            _ => {
                out.push_str(&format!("DB {number}\n"));
                count += 1;
                for i in 0..60 {
                    out.push_str(&format!("  {i}:  KF +{}\n", i * 7));
                    count += 1;
                }
                continue;
            }
        }
        out.push_str("      BE\n");
        count += 1;
    }
    out
}

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
