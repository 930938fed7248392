//! `results_table` and `results_csv` hold the same results: the CSV's fields, read back, are the
//! table's values (numbers bit for bit, an undefined metric an empty field and a null, a
//! reason's line breaks spaces in both).

use tumble_output::table::Values;
use tumble_studies::sweep::{PointRow, Status, SweepDefinition, results_csv, results_table};

const SWEEP: &str = r#"
scene = "free-hoop"

[run]
integrator = "gauss8"
dt = 0.01
t_end = 1.0

[[axes]]
parameter = "omega0"
range = [1.0, 2.0]
count = 3

[metrics]
record = ["max_tilt", "time_tilt_exceeds"]
tilt_threshold = 0.3
"#;

#[test]
fn the_parquet_table_holds_the_values_of_results_csv() {
    let def = SweepDefinition::parse(SWEEP, "test", &[]).unwrap();
    let rows: Vec<PointRow> = (0..3)
        .map(|index| PointRow {
            index,
            values: def.point(index),
            metrics: vec![Some(0.1 + index as f64 / 3.0), (index == 1).then_some(-0.0)],
            status: if index == 2 {
                Status::Failed
            } else {
                Status::Ok
            },
            reason: if index == 2 {
                "diverged\nat t = 1".into()
            } else {
                String::new()
            },
        })
        .collect();
    let table = results_table(&def, &rows, vec![("k".into(), "v".into())]);
    let csv = String::from_utf8(results_csv(&def, &rows).unwrap()).unwrap();
    let mut reader = csv::Reader::from_reader(csv.as_bytes());
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let names: Vec<&str> = table.columns.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(header, names);
    let records: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), rows.len());
    for (k, column) in table.columns.iter().enumerate() {
        for (r, record) in records.iter().enumerate() {
            let field = &record[k];
            match &column.values {
                Values::I64(v) => assert_eq!(field.parse::<i64>().unwrap(), v[r]),
                Values::F64(v) => {
                    assert_eq!(field.parse::<f64>().unwrap().to_bits(), v[r].to_bits())
                }
                Values::OptionalF64(v) => match v[r] {
                    None => assert_eq!(field, ""),
                    Some(x) => assert_eq!(field.parse::<f64>().unwrap().to_bits(), x.to_bits()),
                },
                Values::Text(v) => assert_eq!(field, v[r]),
            }
        }
    }
    assert!(matches!(&table.columns[0].values, Values::I64(_)));
    assert_eq!(table.metadata, vec![("k".to_string(), "v".to_string())]);
    let Values::Text(reasons) = &table.columns.last().unwrap().values else {
        panic!("reason is text")
    };
    assert_eq!(reasons[2], "diverged at t = 1");
}
