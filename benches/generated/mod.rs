//! The generated STEP 5 program the front-end and language-server benchmarks read.

/// A program of realistic shape: PBs of bit logic, word arithmetic and timers, FBs with
/// parameters and labels, calls with parameter lines, and data blocks.
pub fn generate(lines: usize) -> String {
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

/// A STEP 7 source of about `lines` lines: FCs of networks with bit logic, word arithmetic
/// on a DB and a conditional jump, and the OB 1 that calls them.
#[allow(dead_code)] // The front-end benchmark reads only the STEP 5 program.
pub fn generate_step7(lines: usize) -> String {
    let mut out = String::with_capacity(lines * 24);
    let mut count = 0;
    let mut functions = 0;
    while count < lines {
        functions += 1;
        out.push_str(&format!(
            "FUNCTION FC {functions} : VOID\nVAR_TEMP\n  count : INT;\nEND_VAR\nBEGIN\n"
        ));
        count += 5;
        for i in 0..25 {
            out.push_str(&format!(
                "NETWORK\nTITLE = step {i}\n      A     I {}.{};\n      AN    M {}.{};\n      =     Q {}.{};\n      L     DB1.DBW {};\n      L     {};\n      +I    ;\n      T     #count;\n      JP    M{i:03};\n      T     MW {};\nM{i:03}: NOP 0;\n",
                i % 100, i % 8, (i + 3) % 200, (i + 1) % 8, i % 100, (i + 2) % 8, i * 2 % 200, i + 1, (i * 2 + 2) % 200
            ));
            count += 12;
        }
        out.push_str("END_FUNCTION\n\n");
        count += 2;
    }
    out.push_str("DATA_BLOCK DB 1\nSTRUCT\n  words : ARRAY [0..127] OF INT;\nEND_STRUCT\nBEGIN\nEND_DATA_BLOCK\n\n");
    out.push_str("ORGANIZATION_BLOCK OB 1\nVAR_TEMP\n  info : ARRAY [0..19] OF BYTE;\nEND_VAR\nBEGIN\nNETWORK\n");
    for number in 1..=functions {
        out.push_str(&format!("      CALL  FC {number};\n"));
    }
    out.push_str("END_ORGANIZATION_BLOCK\n");
    out
}
